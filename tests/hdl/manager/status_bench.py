"""cocotb bench of status_inserter: chunks through, requests at random moments."""

from __future__ import annotations

import json
import random
from pathlib import Path

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge, SimTimeoutError, with_timeout
from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamSink, AxiStreamSource

from tests.support.axis_bench import bench_case, pauses, start


@cocotb.test()
async def answers_every_request(dut):
    case = bench_case()
    rng = random.Random(case["seed"])
    dut.request.value = 0
    dut.counters.value = 0
    await start(dut)
    source = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s"), dut.clk, dut.rst)
    source.set_pause_generator(pauses(rng, case["idle"]))
    sink = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m"), dut.clk, dut.rst)
    sink.set_pause_generator(pauses(rng, case["backpressure"]))
    for chunk in case["chunks"]:
        await source.send(AxiStreamFrame(bytes.fromhex(chunk)))
    frames = []
    for reading in case["readings"]:
        await ClockCycles(dut.clk, rng.randrange(1, 40))
        dut.counters.value = sum(value << (32 * i) for i, value in enumerate(reading))
        dut.request.value = 1
        await RisingEdge(dut.clk)
        dut.request.value = 0
        while True:  # the counters hold until the answer has started
            try:
                frame = await with_timeout(sink.recv(), 200, "us")
            except SimTimeoutError:
                break  # no answer: the test finds it missing
            frames.append(bytes(frame.tdata).hex())
            if frames[-1].startswith("ffff"):
                break
    await source.wait()
    for _ in range(20_000):
        if len(frames) == len(case["chunks"]) + len(case["readings"]):
            break
        if not sink.empty():
            frames.append(bytes(sink.recv_nowait().tdata).hex())
        await RisingEdge(dut.clk)
    Path(case["result"]).write_text(json.dumps(frames))
