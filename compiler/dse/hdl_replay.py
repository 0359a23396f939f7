"""cocotb test: replay a recorded trace on a generated scheduler and compare every grant.

`rfc.dse.verify.replay_in_ghdl` (used by `rfc dse --verify-hdl` and the co-simulation tests)
converts the scheduler to VHDL and runs this module in GHDL with the trace's path in
SCHED_TRACE. Every cycle the test
drives request/last/ready, lets the logic settle, reads the grant and checks it is one-hot (or
zero) and equal to the model's; the grants are written to SCHED_GRANTS for the property checks.
"""

from __future__ import annotations

import json
import os
from typing import Any

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, ReadOnly, RisingEdge

from rfc.dse.trace import one_hot_index


@cocotb.test()
async def replay_trace(dut: Any) -> None:  # its signals are known when GHDL elaborates it
    """Drive the trace's inputs cycle by cycle; the grant must equal the recorded one."""
    with open(os.environ["SCHED_TRACE"]) as source:
        trace = json.load(source)
    Clock(dut.clk, 10, unit="ns").start()  # cocotb 2: the clock runs its own task
    dut.rst.value = 1
    dut.request.value = 0
    dut.last.value = 0
    dut.ready.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    grants = []
    mismatch = None
    for k, (request, last, ready, expected) in enumerate(
        zip(trace["request"], trace["last"], trace["ready"], trace["grant"], strict=True)
    ):
        dut.request.value = request
        dut.last.value = last
        dut.ready.value = ready
        await ReadOnly()
        actual = one_hot_index(int(dut.grant.value))
        grants.append(actual)
        if actual != expected and mismatch is None:
            mismatch = (
                f"cycle {k}: model grants {expected}, GHDL {actual} "
                f"(request {request:#x}, last {last:#x}, ready {ready})"
            )
            break
        await RisingEdge(dut.clk)
    with open(os.environ["SCHED_GRANTS"], "w") as out:
        json.dump(grants, out)
    assert mismatch is None, mismatch
