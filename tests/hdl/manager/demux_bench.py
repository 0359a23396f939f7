"""cocotb bench of chunk_demux: chunks in through cocotbext-axi, payloads out per subscriber."""

from __future__ import annotations

import random

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge
from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamSource

from tests.support.axis_bench import VectorSink, bench_case, pauses, start


@cocotb.test()
async def routes_every_chunk(dut):
    case = bench_case()
    rng = random.Random(case["seed"])
    await start(dut)
    source = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s"), dut.clk, dut.rst)
    source.set_pause_generator(pauses(rng, case["idle"]))
    sink = VectorSink(dut, "m", case["subscribers"], case["width"], rng, case["backpressure"])
    for chunk in case["chunks"]:
        await source.send(AxiStreamFrame(bytes.fromhex(chunk)))
    await source.wait()
    expected = case["expected"]
    for _ in range(10_000):
        if [len(p) for p in sink.packets] == [len(p) for p in expected]:
            break
        await RisingEdge(dut.clk)
    await ClockCycles(dut.clk, 10)
    assert [[p.hex() for p in packets] for packets in sink.packets] == expected
    assert sink.null_beats == case["null_beats"]
    assert int(dut.error_count.value) == case["errors"]
