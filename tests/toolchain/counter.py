"""A tiny MyHDL design and its cocotb tests, for checking the toolchain wrappers."""

from __future__ import annotations

import os

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, ReadOnly, RisingEdge
from myhdl import ResetSignal, Signal, always_comb, always_seq, block, intbv, modbv


@block
def counter(clk, rst, enable, count, width=8):
    state = Signal(modbv(0)[width:])

    @always_seq(clk.posedge, reset=rst)
    def step():
        if enable:
            state.next = state + 1

    @always_comb
    def drive():
        count.next = state

    return step, drive


def counter_instance(width=8):
    return counter(
        Signal(bool(0)),
        ResetSignal(0, active=1, isasync=False),
        Signal(bool(0)),
        Signal(intbv(0)[width:]),
        width=width,
    )


@cocotb.test()
async def counts_enabled_cycles(dut):
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.rst.value = 1
    dut.enable.value = 0
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    dut.enable.value = 1
    cycles = int(os.environ.get("COUNTER_CYCLES", "5"))
    await ClockCycles(dut.clk, cycles)
    await ReadOnly()
    expected = int(os.environ.get("COUNTER_EXPECT", str(cycles)))
    assert int(dut.count.value) == expected, f"count {int(dut.count.value)} != {expected}"
    await RisingEdge(dut.clk)
