"""The ap_fifo width adapters: beats to elements and back, against NumPy's view of the bytes.

Under random valid/ready on both sides every element comes out once, in order (the bytes of
the beats read as little-endian elements by NumPy), a partial last beat included; the packer
sends ceil(length · element / beat) beats per message, the last when the message is flushed.
Both convert to VHDL that GHDL analyses and elaborates.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance, intbv

from rfc.lib.hls.streams import pack_elements, unpack_beats
from rfc.toolchain.convert import convert_myhdl
from rfc.toolchain.ghdl import analyze

CYCLES = 5000
SHAPES = [(8, 1), (8, 2), (8, 8), (4, 4), (1, 1)]  # (beat bytes, element bytes)


def clocked():
    return Signal(bool(0)), ResetSignal(0, active=1, isasync=False)


def unpack(beat: int, element: int, data: bytes, seed: int) -> list[int]:
    clk, rst = clocked()
    tdata, tkeep = Signal(intbv(0)[8 * beat :]), Signal(intbv(0)[beat:])
    tvalid, tready, empty_n, read = (Signal(bool(0)) for _ in range(4))
    dout = Signal(intbv(0)[8 * element :])
    beats = [data[i : i + beat] for i in range(0, len(data), beat)]
    out: list[int] = []

    @block
    def bench():
        dut = unpack_beats(clk, rst, tdata, tkeep, tvalid, tready, dout, empty_n, read)

        @always(delay(5))
        def tick():
            clk.next = not clk

        @instance
        def drive():
            rng, sent = random.Random(seed), 0
            for _ in range(CYCLES):  # a stall ends the run with what came out
                if len(out) == len(data) // element:
                    break
                yield clk.negedge
                if not tvalid and sent < len(beats) and rng.random() < 0.7:
                    chunk = beats[sent]
                    tdata.next = int.from_bytes(chunk.ljust(beat, b"\0"), "little")
                    tkeep.next = (1 << len(chunk)) - 1
                    tvalid.next = 1
                read.next = rng.random() < 0.6
                yield clk.posedge
                if empty_n and read:
                    out.append(int(dout))
                if tvalid and tready:
                    sent += 1
                    tvalid.next = 0
            raise StopSimulation

        return dut, tick, drive

    bench().run_sim(quiet=1)
    return out


def pack(beat: int, element: int, messages: list[np.ndarray], seed: int) -> list[bytes]:
    clk, rst = clocked()
    din = Signal(intbv(0)[8 * element :])
    full_n, write, flush, tvalid, tready = (Signal(bool(0)) for _ in range(5))
    tdata = Signal(intbv(0)[8 * beat :])
    received: list[bytes] = []
    total = sum(-(-len(m) * element // beat) for m in messages)

    @block
    def bench():
        dut = pack_elements(clk, rst, din, full_n, write, flush, tdata, tvalid, tready)

        @always(delay(5))
        def tick():
            clk.next = not clk

        @instance
        def drive():  # a message's elements, then one flush pulse (ap_done), then the next
            rng = random.Random(seed)
            pending = [list(m) for m in messages]
            for _ in range(CYCLES):  # a stall ends the run with what came out
                if len(received) == total:
                    break
                yield clk.negedge
                flush.next = bool(pending) and not pending[0] and rng.random() < 0.5
                if pending and pending[0]:
                    din.next = int(pending[0][0])
                write.next = bool(pending) and bool(pending[0]) and rng.random() < 0.7
                tready.next = rng.random() < 0.6
                yield clk.posedge
                if write and full_n:
                    pending[0].pop(0)
                if flush:
                    pending.pop(0)
                if tvalid and tready:
                    received.append(int(tdata).to_bytes(beat, "little"))
            raise StopSimulation

        return dut, tick, drive

    bench().run_sim(quiet=1)
    return received


@pytest.mark.parametrize(("beat", "element"), SHAPES)
def test_beats_become_the_elements_numpy_reads_in_their_bytes(beat, element):
    rng = np.random.default_rng(beat * 10 + element)
    for count in (1, 5, 17):
        data = rng.integers(0, 256, size=count * element, dtype=np.uint8).tobytes()
        expected = np.frombuffer(data, dtype=f"<u{element}").tolist()
        assert unpack(beat, element, data, seed=count) == expected


@pytest.mark.parametrize(("beat", "element"), SHAPES)
def test_elements_become_beats_with_a_partial_last_beat_at_each_flush(beat, element):
    rng = np.random.default_rng(beat * 10 + element)
    messages = [rng.integers(0, 2 ** (8 * element), size=n, dtype=np.uint64) for n in (5, 1, 9)]
    beats = pack(beat, element, messages, seed=beat + element)
    start = 0
    for message in messages:
        used = -(-len(message) * element // beat)
        sent = b"".join(beats[start : start + used])
        start += used
        expected = message.astype(f"<u{element}").tobytes()
        assert sent == expected.ljust(used * beat, b"\0")
    assert start == len(beats)


def test_both_convert_to_vhdl_that_ghdl_elaborates(tmp_path):
    clk, rst = clocked()
    tdata, tkeep = Signal(intbv(0)[64:]), Signal(intbv(0)[8:])
    din, dout = Signal(intbv(0)[16:]), Signal(intbv(0)[16:])
    flags = [Signal(bool(0)) for _ in range(8)]
    unpacker = unpack_beats(clk, rst, tdata, tkeep, flags[0], flags[1], dout, flags[2], flags[3])
    files = convert_myhdl(unpacker, "unpack_beats_test", tmp_path, verilog=False)
    analyze(files, tmp_path, top="unpack_beats_test")
    beat = Signal(intbv(0)[64:])
    packer = pack_elements(clk, rst, din, flags[4], flags[5], flags[7], beat, flags[6], flags[0])
    files = convert_myhdl(packer, "pack_elements_test", tmp_path / "pack", verilog=False)
    analyze(files, tmp_path / "pack", top="pack_elements_test")
