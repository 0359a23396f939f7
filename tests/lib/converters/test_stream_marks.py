"""`stream_marks`: keep and last of an accelerator's sub-stream, from its length alone.

Messages of random lengths go through back to back with random gaps; each beat's keep and
last must be what a subscriber gives: every beat full but the last, whose keep covers the
elements left, and last on the final beat only.
"""

from __future__ import annotations

import numpy as np
import pytest
from myhdl import ResetSignal, Signal, Simulation, StopSimulation, delay, instance, intbv

from rfc.lib.converters.stream_marks import stream_marks


def expected_marks(length: int, beat: int, element: int) -> list[tuple[int, bool]]:
    """Keep and last of each beat of a stream of `length` elements (Python, from the rule)."""
    per_beat = beat // element
    beats = -(-length // per_beat)
    marks = []
    for index in range(beats):
        elements = min(per_beat, length - index * per_beat)
        marks.append(((1 << (elements * element)) - 1, index == beats - 1))
    return marks


@pytest.mark.parametrize(("beat", "element"), [(8, 1), (8, 4), (4, 4), (8, 8), (1, 1)])
def test_each_beat_gets_the_keep_and_last_a_subscriber_gives(beat, element):
    rng = np.random.default_rng(beat * 10 + element)
    lengths = [int(n) for n in rng.integers(1, 40, size=30)]
    clk, rst = Signal(bool(0)), ResetSignal(1, active=1, isasync=False)
    length = Signal(intbv(0)[16:])
    tvalid, tready, tlast = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    tkeep = Signal(intbv(0)[beat:])
    dut = stream_marks(element, clk=clk, rst=rst, length=length, tvalid=tvalid, tready=tready,
                       tkeep=tkeep, tlast=tlast)  # fmt: skip
    seen: list[tuple[int, bool]] = []

    @instance
    def clock():
        while True:
            yield delay(5)
            clk.next = not clk

    @instance
    def stimulus():
        yield clk.posedge
        rst.next = 0
        for count in lengths:
            length.next = count
            for _ in expected_marks(count, beat, element):
                tvalid.next = 1
                tready.next = bool(rng.random() < 0.6)
                yield clk.posedge
                while not tready:
                    tready.next = bool(rng.random() < 0.6)
                    yield clk.posedge
                seen.append((int(tkeep), bool(tlast)))
                tvalid.next = 0
                tready.next = 0
                if rng.random() < 0.3:
                    yield clk.posedge
        raise StopSimulation

    Simulation(dut, clock, stimulus).run(quiet=True)
    assert seen == [mark for n in lengths for mark in expected_marks(n, beat, element)]
