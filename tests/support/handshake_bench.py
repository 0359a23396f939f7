"""cocotb bench: stream items through a valid/ready block with random idle and backpressure.

One loop per clock edge: values read just after a rising edge are those the design sampled at
it. An item is taken on an edge where in_valid and in_ready were high; its latency is the
number of edges from there until out_valid was high, less one (out_valid high on the cycle
after edge k + latency). A result is taken on an edge where out_valid and out_ready were high.
"""

from __future__ import annotations

import json
import os
import random
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge


@cocotb.test()
async def stream_items(dut):
    job = json.loads(Path(os.environ["RFC_JOB"]).read_text())
    rng = random.Random(job["seed"])
    inputs, expected = job["inputs"], job["expected"]
    count = len(next(iter(inputs.values())))
    ports = {name: getattr(dut, name) for name in (*inputs, *job["outputs"])}
    seen = {name: [] for name in job["outputs"]}
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.rst.value = 1
    dut.in_valid.value = 0
    dut.out_ready.value = 0
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0

    sent = edge = last_progress = 0
    taken_at: list[int] = []
    valid_at: list[int] = []
    offering = False
    while len(seen[job["outputs"][0]]) < count:
        if not offering and sent < count and rng.random() >= job["idle"]:
            for name, values in inputs.items():
                ports[name].value = values[sent]
            offering = True
        dut.in_valid.value = int(offering)
        out_ready = rng.random() >= job["backpressure"]
        dut.out_ready.value = int(out_ready)
        await RisingEdge(dut.clk)
        edge += 1
        if offering and int(dut.in_ready.value):
            taken_at.append(edge)
            sent += 1
            offering = False
            last_progress = edge
        if int(dut.out_valid.value):
            if len(valid_at) == len(seen[job["outputs"][0]]):
                valid_at.append(edge)
            if out_ready:
                for name in seen:
                    seen[name].append(int(ports[name].value))
                last_progress = edge
        assert edge - last_progress < job["timeout"], (
            f"no progress for {job['timeout']} cycles after {sent} items in, "
            f"{len(seen[job['outputs'][0]])} out: the block hangs"
        )
    dut.in_valid.value = 0
    latencies = [valid - taken - 1 for taken, valid in zip(taken_at, valid_at, strict=True)]
    Path(job["result"]).write_text(json.dumps({"outputs": seen, "latencies": latencies}))
    mismatches = [
        f"item {i} {name}: got {got:#x}, expected {want:#x}"
        for name, wanted in expected.items()
        for i, (got, want) in enumerate(zip(seen[name], wanted, strict=True))
        if got != want
    ]
    assert not mismatches, f"{len(mismatches)} mismatches: " + "; ".join(mismatches[:5])
