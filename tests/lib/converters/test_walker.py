"""The step walker on its own, let go every cycle: it must cut the codec's frame where it is cut.

Whatever a converter adds, the frame's layout is the walker's: the bytes its steps move (record
chunks, CDR alignment pads before fields and before a sequence's first element, payload chunks)
must add up to the frame the reference codec (held to rosbags) encodes, and the characters and
elements it marks in that frame must be the sub-streams' bytes, in order.
"""

from __future__ import annotations

import pytest
from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance

from rfc.lib.converters.plan import plan
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.tables import Kind, tables
from rfc.lib.converters.transactions import transactions
from rfc.lib.converters.walker import Walk, step_walker
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from tests.hdl.converters.matrix import drawn_values

LIMITS = Limits(string=64, sequence=16, frame=4096)


def walk_over(converters: Plan, frame: bytes, payload_bytes: list[int]) -> tuple[int, bytes]:
    """Walk the plan once over `frame`: the bytes moved, and those it marks as characters.

    `payload_bytes`: what each payload holds as the walk enters it, in frame order.
    """
    t = tables(converters)
    walk = Walk.of(converters)
    clk, rst, more = Signal(bool(0)), ResetSignal(0, active=1, isasync=False), Signal(bool(0))
    moved = [0]
    marked = bytearray()

    @block
    def bench():
        walker = step_walker(converters, clk, rst, walk, more)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            remaining = list(payload_bytes)
            while True:
                yield clk.negedge  # what the walk shows now moves at the next rising edge
                walk.go.next = True
                kind = t.kind[int(walk.pc)]
                if kind == Kind.END:
                    raise StopSimulation
                if kind == Kind.PAYLOAD and not walk.entered:
                    walk.rem_start.next = remaining.pop(0)
                marked.extend(frame[moved[0] : moved[0] + int(walk.chars)])
                moved[0] += int(walk.size)

        return walker, clock, drive

    simulation = bench()
    simulation.run_sim(quiet=1)
    simulation.quit_sim()
    return moved[0], bytes(marked)


@pytest.mark.parametrize("width", [8, 32, 64])
@pytest.mark.parametrize("middleware", list(Middleware))
@pytest.mark.parametrize("type_name", ["sensor_msgs/msg/Image", "sensor_msgs/msg/CameraInfo"])
def test_the_walk_cuts_the_frame_as_the_codec_does(type_name, middleware, width):
    layout = flatten(message_types(middleware), type_name)
    converters = plan(layout, width, LIMITS)
    payloads = [converters.payload(at) for at in tables(converters).streams]
    for values in drawn_values(layout, f"walker {type_name} {middleware.value} {width}", 3):
        taken = transactions(converters, values)
        contents = [data for p in payloads for data in taken.streams[p.stream]]
        # as the converters load it: the elements' bytes, and a CDR string's NUL
        held = [len(data) + p.terminator for p, data in zip(payloads, contents, strict=True)]
        frame = encode(layout, values)

        moved, marked = walk_over(converters, frame, held)

        assert moved == len(frame)
        assert marked == b"".join(contents)
