"""The step walker on its own, let go every cycle: it must cut the codec's frame where it is cut.

Whatever a converter adds, the frame's layout is the walker's: the bytes its steps move (record
chunks, CDR alignment pads before fields and before a sequence's first element, payload chunks,
elements of sequences over and over) must add up to the frame the reference codec (held to
rosbags) encodes, and the characters and elements it marks in that frame must be each
sub-stream's bytes. The bench reads lengths and counts from the frame as a subscriber would:
the four bytes before a string, a sequence or a loop.
"""

from __future__ import annotations

import pytest
from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance, intbv

from rfc.lib.converters.plan import plan
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.tables import Kind, tables
from rfc.lib.converters.transactions import transactions
from rfc.lib.converters.walker import Walk, step_walker
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.toolchain import elaboration
from tests.hdl.converters.matrix import drawn_values

LIMITS = Limits(string=64, sequence=16, frame=4096)

TYPES = [
    ("sensor_msgs/msg/Image", Middleware.ROS2),
    ("sensor_msgs/msg/Image", Middleware.ROS1),
    ("sensor_msgs/msg/CameraInfo", Middleware.ROS2),
    ("sensor_msgs/msg/JointState", Middleware.ROS2),
    ("sensor_msgs/msg/JointState", Middleware.ROS1),
    ("tf2_msgs/msg/TFMessage", Middleware.ROS2),
]


def walk_over(converters: Plan, frame: bytes) -> tuple[int, dict[str, list[bytes]]]:
    """Walk the plan once over `frame`: the bytes moved, and per sub-stream what it marks."""
    t = tables(converters)
    walk = Walk.of(converters)
    clk, rst = Signal(bool(0)), ResetSignal(0, active=1, isasync=False)
    count = Signal(intbv(0)[32:])
    moved = [0]
    marked: dict[str, list[bytearray]] = {}

    @block
    def bench():
        walker = step_walker(converters, clk, rst, walk, count)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            while True:
                yield clk.negedge  # what the walk shows now moves at the next rising edge
                walk.go.next = True
                at = int(walk.pc)
                kind = t.kind[at]
                length = int.from_bytes(frame[moved[0] - 4 : moved[0]], "little")
                if kind == Kind.END:
                    raise StopSimulation
                walk.skip.next = kind == Kind.LOOP and length == 0
                if kind == Kind.LOOP:
                    count.next = length
                if kind == Kind.PAYLOAD and not walk.entered:
                    count.next = length - t.terminator[at]  # a CDR string's counts its NUL
                    stream = converters.payload(at).stream
                    marked.setdefault(stream, []).append(bytearray())
                if kind == Kind.PAYLOAD and walk.entered:
                    instances = marked[converters.payload(at).stream]
                    instances[-1].extend(frame[moved[0] : moved[0] + int(walk.chars)])
                moved[0] += int(walk.size)

        return walker, clock, drive

    with elaboration():
        simulation = bench()
    simulation.run_sim(quiet=1)
    simulation.quit_sim()
    return moved[0], {name: [bytes(b) for b in found] for name, found in marked.items()}


@pytest.mark.parametrize("width", [8, 32, 64])
@pytest.mark.parametrize(
    ("type_name", "middleware"), TYPES, ids=[f"{n.rsplit('/', 1)[-1]}-{m.value}" for n, m in TYPES]
)
def test_the_walk_cuts_the_frame_as_the_codec_does(type_name, middleware, width):
    layout = flatten(message_types(middleware), type_name)
    converters = plan(layout, width, LIMITS)
    for values in drawn_values(layout, f"walker {type_name} {middleware.value} {width}", 3):
        frame = encode(layout, values)

        moved, marked = walk_over(converters, frame)

        assert moved == len(frame)
        streams = transactions(converters, values).streams
        assert marked == {name: found for name, found in streams.items() if found}
