"""cocotb bench: stream items through a valid/ready block with random idle and backpressure.

Values read just after a rising edge are those the design sampled at it. An item is taken on an
edge where in_valid and in_ready were high; its latency is the number of cycles from there until
out_valid rose (out_valid is high on the cycle after edge k + latency). A result is taken on an
edge where out_valid and out_ready were high. While the block can neither take an item nor give
a result, the bench sleeps until in_ready or out_valid rises instead of visiting every edge.
"""

from __future__ import annotations

import json
import os
import random
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, First, RisingEdge, Timer
from cocotb.utils import get_sim_time

PERIOD_NS = 10


@cocotb.test()
async def stream_items(dut):
    job = json.loads(Path(os.environ["RFC_JOB"]).read_text())
    rng = random.Random(job["seed"])
    inputs, expected = job["inputs"], job["expected"]
    count = len(next(iter(inputs.values())))
    ports = {name: getattr(dut, name) for name in (*inputs, *job["outputs"])}
    seen = {name: [] for name in job["outputs"]}
    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    dut.rst.value = 1
    dut.in_valid.value = 0
    dut.out_ready.value = 0
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0

    def cycle() -> int:
        return round(get_sim_time("ns") / PERIOD_NS)

    sent = taken = 0
    last_progress = cycle()
    taken_at: list[int] = []
    valid_at: list[int] = []
    offering = False
    while taken < count:
        if not offering and sent < count and rng.random() >= job["idle"]:
            for name, values in inputs.items():
                ports[name].value = values[sent]
            offering = True
        dut.in_valid.value = int(offering)
        out_ready = rng.random() >= job["backpressure"]
        dut.out_ready.value = int(out_ready)
        await RisingEdge(dut.clk)
        now = cycle()
        if offering and int(dut.in_ready.value):
            taken_at.append(now)
            sent += 1
            offering = False
            last_progress = now
        out_valid = int(dut.out_valid.value)
        if out_valid:
            if len(valid_at) == taken:
                valid_at.append(now)
            if out_ready:
                for name in seen:
                    seen[name].append(int(ports[name].value))
                taken += 1
                last_progress = now
        assert now - last_progress < job["timeout"], (
            f"no progress for {job['timeout']} cycles after {sent} items in, {taken} out: "
            "the block hangs"
        )
        if not out_valid and not int(dut.in_ready.value) and (offering or sent == count):
            # Busy: nothing to sample until the block offers a result or asks for an item.
            busy = First(RisingEdge(dut.out_valid), RisingEdge(dut.in_ready))
            await First(busy, Timer(job["timeout"] * PERIOD_NS, unit="ns"))
            await Timer(1, unit="ns")
    dut.in_valid.value = 0
    latencies = [valid - start - 1 for start, valid in zip(taken_at, valid_at, strict=True)]
    Path(job["result"]).write_text(
        json.dumps({"outputs": seen, "latencies": latencies, "accepted": taken_at})
    )
    mismatches = [
        f"item {i} {name}: got {got:#x}, expected {want:#x}"
        for name, wanted in expected.items()
        for i, (got, want) in enumerate(zip(seen[name], wanted, strict=True))
        if got != want
    ]
    assert not mismatches, f"{len(mismatches)} mismatches: " + "; ".join(mismatches[:5])
