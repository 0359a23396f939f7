"""The chunk-length snooper in MyHDL's simulator, against headers packed as docs/protocol.md says.

Chunks for several subscribers (``<HHI``: id, flags, length, then the payload) pass the
snooped stream with random idle cycles and back-pressure; after each chunk the snooper of one
subscriber must hold the length of the last header that named it, and only that.
"""

from __future__ import annotations

import random
import struct

import pytest
from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance, intbv

from rfc.lib.converters.chunk_length import LENGTH_BITS, chunk_length
from rfc.lib.converters.toplevel import elaboration

IDENT = 2


def chunks(rng: random.Random) -> list[tuple[int, bytes]]:
    """Chunks for subscribers 0 to 3: payloads of 0 to 40 bytes (header only when empty)."""
    found = []
    for _ in range(24):
        ident, size = rng.randrange(4), rng.randrange(41)
        length = size if rng.random() < 0.8 else rng.randrange(2**32)  # the header may lie
        payload = bytes(rng.randrange(256) for _ in range(size))
        found.append((ident, struct.pack("<HHI", ident, 3, length) + payload))
    return found


@pytest.mark.parametrize("width", [8, 32, 64])
def test_the_snooper_holds_the_length_of_its_subscribers_last_header(width):
    lanes = width // 8
    rng = random.Random(width)
    sent = chunks(rng)
    clk, rst = Signal(bool(0)), ResetSignal(1, active=1, isasync=False)
    tdata, tvalid, tready, tlast = (Signal(intbv(0)[width:]), Signal(bool(0)), Signal(bool(0)),
                                    Signal(bool(0)))  # fmt: skip
    length = Signal(intbv(0)[LENGTH_BITS:])
    seen: list[int] = []

    @block
    def bench():
        dut = chunk_length(clk, rst, IDENT, tdata, tvalid, tready, tlast, length)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @always(clk.posedge)
        def back_pressure():
            tready.next = rng.random() < 0.7

        @instance
        def drive():
            yield clk.posedge
            rst.next = 0
            for _, chunk in sent:
                beats = [chunk[i : i + lanes] for i in range(0, len(chunk), lanes)]
                for index, beat in enumerate(beats):
                    while rng.random() < 0.3:
                        tvalid.next = 0
                        yield clk.posedge
                    tdata.next = int.from_bytes(beat.ljust(lanes, b"\0"), "little")
                    tlast.next = index == len(beats) - 1
                    tvalid.next = 1
                    yield clk.posedge
                    while not tready:
                        yield clk.posedge
                tvalid.next = 0
                yield clk.posedge
                seen.append(int(length))
            raise StopSimulation

        return dut, clock, back_pressure, drive

    with elaboration():
        bench().run_sim(quiet=1)
    held, expected = 0, []
    for ident, chunk in sent:
        if ident == IDENT:
            held = struct.unpack_from("<I", chunk, 4)[0]
        expected.append(held)
    assert seen == expected
    assert len({ident for ident, _ in sent}) > 1
    assert IDENT in {ident for ident, _ in sent}
