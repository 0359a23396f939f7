"""MyHDL's Verilog, as rfc writes it, computes what MyHDL's own simulator computes.

MyHDL declares an undriven signal (a constant) and a ``Constant`` without ``signed`` in Verilog,
so a signed operand compared with a negative constant was compared as unsigned in Verilator.
"""

from __future__ import annotations

from typing import Any

import pytest
from myhdl import Constant, Signal, always_comb, block, delay, instance, intbv

from rfc.toolchain import convert_myhdl
from rfc.toolchain.verilator import run_testbench


def signed(value: int, bits: int) -> intbv:
    return intbv(value, min=-(1 << (bits - 1)), max=1 << (bits - 1))


@block
def clamp(a: Any, y: Any, low: int, high: int) -> Any:
    """`a` clamped to [low, high]: the bounds are an undriven signal and a Constant."""
    bits = len(a)
    lower = Signal(signed(low, bits))  # nothing drives it: MyHDL writes a constant wire
    upper = Constant(signed(high, bits))

    @always_comb
    def limit() -> None:
        if a < lower:
            y.next = lower
        elif a > upper:
            y.next = upper
        else:
            y.next = a

    return limit


def inputs(bits: int, low: int, high: int) -> list[int]:
    top = 1 << (bits - 1)
    return [-top, low - 1, low, low + 1, -1, 0, 1, high - 1, high, high + 1, top - 1]


def myhdl_outputs(bits: int, low: int, high: int) -> list[int]:
    seen: list[int] = []

    @block
    def bench() -> Any:
        a, y = Signal(signed(0, bits)), Signal(signed(0, bits))

        @instance
        def drive() -> Any:
            for value in inputs(bits, low, high):
                a.next = value
                yield delay(1)
                seen.append(int(y.val))

        return clamp(a, y, low, high), drive

    bench().run_sim(quiet=1)
    return seen


def verilator_outputs(tmp_path, bits: int, low: int, high: int) -> list[int]:
    a, y = Signal(signed(0, bits)), Signal(signed(0, bits))
    with pytest.warns(UserWarning, match="not driven: lower"):
        files = convert_myhdl(clamp(a, y, low, high), "clamp", tmp_path / "hdl")
    steps = "".join(f"a = {bits}'sd{v % (1 << bits)}; #1 $display(\"y=%0d\", y);\n" for v in
                    inputs(bits, low, high))  # fmt: skip
    bench = tmp_path / "clamp_tb.v"
    bench.write_text(
        "module clamp_tb;\n"
        f"reg signed [{bits - 1}:0] a;\nwire signed [{bits - 1}:0] y;\n"
        "clamp dut(.a(a), .y(y));\n"
        f"initial begin\n{steps}$finish;\nend\nendmodule\n"
    )
    printed = run_testbench([files[-1], bench], "clamp_tb", {}, {}, tmp_path / "run")
    return [int(line[2:]) for line in printed.splitlines() if line.startswith("y=")]


@pytest.mark.parametrize("bits", [4, 50], ids=["4-bit", "50-bit"])
def test_signed_constants_bound_the_same_in_verilator_as_in_myhdl(tmp_path, monkeypatch, bits):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    low, high = -(1 << (bits - 2)) + 3, 1 << (bits - 3)
    expected = [min(max(value, low), high) for value in inputs(bits, low, high)]
    assert myhdl_outputs(bits, low, high) == expected
    assert verilator_outputs(tmp_path, bits, low, high) == expected
