"""The DMA tap in MyHDL's simulator, against chunk headers packed as docs/protocol.md says.

Chunks for several subscribers (``<HHI``: id, flags, length, then the payload) pass the tap
with random idle cycles and back-pressure; every beat must leave it unchanged, and after each
chunk the tap must hold, for each subscriber it serves, the length of the last header that
named that subscriber, and only that.
"""

from __future__ import annotations

import random
import struct

import pytest
from myhdl import StopSimulation, always, block, delay, instance

from rfc.lib.converters.chunk_length import dma_tap, dma_tap_ports, length_port
from rfc.lib.converters.toplevel import port_signals
from rfc.toolchain import elaboration

SERVED = (2, 0)


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
def test_the_tap_passes_every_beat_and_holds_each_subscribers_last_declared_length(width):
    lanes = width // 8
    rng = random.Random(width)
    sent = chunks(rng)
    signals = port_signals(dma_tap_ports(lanes, SERVED))
    clk = signals["clk"]
    seen: list[tuple[int, ...]] = []
    beats_in: list[tuple[int, int, bool]] = []
    beats_out: list[tuple[int, int, bool]] = []

    @block
    def bench():
        dut = dma_tap(SERVED, **signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @always(clk.posedge)
        def consume():
            if signals["m_axis_tvalid"] and signals["m_axis_tready"]:
                beats_out.append(tuple(int(signals[f"m_axis_{n}"]) for n in ("tdata", "tkeep",
                                 "tlast")))  # fmt: skip
            signals["m_axis_tready"].next = rng.random() < 0.7

        @instance
        def drive():
            signals["rst"].next = 1
            yield clk.posedge
            signals["rst"].next = 0
            for _, chunk in sent:
                beats = [chunk[i : i + lanes] for i in range(0, len(chunk), lanes)]
                for index, beat in enumerate(beats):
                    while rng.random() < 0.3:
                        signals["s_axis_tvalid"].next = 0
                        yield clk.posedge
                    data = int.from_bytes(beat.ljust(lanes, b"\0"), "little")
                    keep, last = (1 << len(beat)) - 1, index == len(beats) - 1
                    signals["s_axis_tdata"].next = data
                    signals["s_axis_tkeep"].next = keep
                    signals["s_axis_tlast"].next = last
                    signals["s_axis_tvalid"].next = 1
                    yield clk.posedge
                    while not signals["s_axis_tready"]:
                        yield clk.posedge
                    beats_in.append((data, keep, int(last)))
                signals["s_axis_tvalid"].next = 0
                yield clk.posedge
                seen.append(tuple(int(signals[length_port(s)]) for s in SERVED))
            raise StopSimulation

        return dut, clock, consume, drive

    with elaboration():
        bench().run_sim(quiet=1)
    held, expected = dict.fromkeys(SERVED, 0), []
    for ident, chunk in sent:
        if ident in held:
            held[ident] = struct.unpack_from("<I", chunk, 4)[0]
        expected.append(tuple(held[s] for s in SERVED))
    assert seen == expected
    assert all(held.values())
    assert beats_out == beats_in
