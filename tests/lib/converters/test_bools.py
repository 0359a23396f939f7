"""bool_bytes: at a bool sequence's step every byte leaves as 0 or 1, elsewhere untouched.

rosbags writes true as 1 and reads any nonzero byte as true (the Python reference below).
"""

from __future__ import annotations

import random

import pytest
from myhdl import Signal, StopSimulation, block, delay, instance, intbv

from rfc.lib.converters.bools import bool_bytes
from rfc.lib.converters.plan import plan
from rfc.lib.converters.steps import Payload
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types


@pytest.mark.parametrize("width", [8, 32, 64])
def test_bool_steps_send_zero_or_one_and_other_steps_every_byte(width, tmp_path):
    folder = tmp_path / "flag_msgs" / "msg"
    folder.mkdir(parents=True)
    (folder / "Flags.msg").write_text("bool[] flags\nuint8[] raw\n")
    types = message_types(Middleware.ROS2, msg_paths=(str(tmp_path),))
    converters = plan(flatten(types, "flag_msgs/msg/Flags"), width, Limits())
    steps = {
        step.field.ros_type: at
        for at, step in enumerate(converters.steps)
        if isinstance(step, Payload)
    }
    lanes = converters.width
    pc = Signal(intbv(0, min=0, max=len(converters.steps)))
    source, out = Signal(intbv(0)[8 * lanes :]), Signal(intbv(0)[8 * lanes :])
    rng = random.Random(width)
    seen = []

    @block
    def bench():
        dut = bool_bytes(converters, pc, source, out)

        @instance
        def drive():
            for _ in range(50):
                data = bytes(
                    rng.choice([0, 1, 2, 0x80, 0xFF, rng.randrange(256)]) for _ in range(lanes)
                )
                for name, at in steps.items():
                    pc.next = at
                    source.next = int.from_bytes(data, "little")
                    yield delay(1)
                    seen.append((name, data, int(out).to_bytes(lanes, "little")))
            raise StopSimulation

        return dut, drive

    simulation = bench()
    simulation.run_sim(quiet=1)
    simulation.quit_sim()

    assert sorted(steps) == ["bool[]", "uint8[]"]
    for name, data, result in seen:
        expected = bytes(int(bool(b)) for b in data) if name == "bool[]" else data
        assert result == expected
