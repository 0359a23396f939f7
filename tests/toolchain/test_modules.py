"""Chosen blocks become Verilog modules of their own, written once, computing the same.

The oracle is MyHDL's own simulation of the design: Verilator runs the Verilog with the
separate modules and must print what MyHDL computed, cycle by cycle.
"""

from __future__ import annotations

from typing import Any

import pytest
from myhdl import Signal, always, always_comb, block, delay, instance, intbv

from rfc.toolchain import convert_myhdl, module_instances, start_new_design
from rfc.toolchain.verilator import run_testbench

BITS = 8
MASK = (1 << BITS) - 1


@block
def mix(clk: Any, a: Any, y: Any, k: int) -> Any:
    """``y`` ← (a + k) xor (a >> 1), registered: a block with a parameter."""

    @always(clk.posedge)
    def step() -> None:
        y.next = ((a + k) & MASK) ^ (a >> 1)

    return step


@block
def total(values: Any, out: Any) -> Any:
    """The sum of a list of signals: a bus MyHDL gives no port of its own."""

    count = len(values)

    @always_comb
    def add() -> None:
        s = intbv(0)[BITS + 2 :]
        for i in range(count):
            s[:] = s + values[i]
        out.next = s[BITS:]

    return add


class Pair:
    """An interface object: two signals as attributes."""

    def __init__(self) -> None:
        self.left, self.right = Signal(intbv(0)[BITS:]), Signal(intbv(0)[BITS:])


@block
def swap(pair: Any, out: Any) -> Any:
    """`out` ← the pair's two halves swapped: a block taking an interface object."""

    @always_comb
    def move() -> None:
        out.next = pair.right ^ pair.left

    return move


@block
def design(clk: Any, a: Any, b: Any, t: Any, u: Any) -> Any:
    """Three `mix` blocks (two alike), glue between them, blocks taking a list or an interface."""
    y, z, w = (Signal(intbv(0)[BITS:]) for _ in range(3))
    blocks = [mix(clk, a, y, 3), mix(clk, b, z, 3), mix(clk, a, w, 5)]
    pair, swapped = Pair(), Signal(intbv(0)[BITS:])

    @always_comb
    def glue() -> None:
        t.next = y ^ z ^ swapped

    summed = total([y, z, w], u)
    crossed = swap(pair, swapped)

    @always_comb
    def load() -> None:
        pair.left.next = a
        pair.right.next = b

    return blocks, glue, summed, crossed, load


def signals() -> dict[str, Any]:
    start_new_design()
    return {
        "clk": Signal(bool(0)),
        "a": Signal(intbv(0)[BITS:]),
        "b": Signal(intbv(0)[BITS:]),
        "t": Signal(intbv(0)[BITS:]),
        "u": Signal(intbv(0)[BITS:]),
    }


STIMULUS = [(3, 250), (17, 4), (255, 255), (0, 1), (128, 64), (99, 1)]


def chosen(block_instance: Any) -> bool:
    return block_instance.func.__name__ in ("mix", "total", "swap")


@pytest.fixture
def converted(tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    instance = design(**signals())
    return convert_myhdl(instance, "parent", tmp_path / "hdl", separate=chosen), instance


def test_blocks_alike_share_one_module_and_a_block_used_once_stays_inline(converted):
    files, _ = converted
    verilog = [f for f in files if f.suffix == ".v"]
    assert verilog[-1].name == "parent.v"  # the parent last, after the modules it instantiates
    modules = [f.stem for f in verilog[:-1]]
    assert len(modules) == 1  # k=3, called twice
    assert modules[0].startswith("mix_")
    parent = verilog[-1].read_text()
    instances = module_instances(parent, modules)
    assert instances == [("mix0", modules[0]), ("mix1", modules[0])]
    # k=5 (called once) and the blocks taking a list or an interface stay inline
    assert parent.count("always @(posedge clk)") == 1
    assert "total" not in " ".join(modules)
    assert "swap" not in " ".join(modules)


def test_the_vhdl_stays_one_entity(converted):
    files, _ = converted
    vhdl = [f for f in files if f.suffix == ".vhd"]
    assert [f.name for f in vhdl] == ["pck_myhdl_011.vhd", "parent.vhd"]
    assert "entity mix" not in vhdl[1].read_text()


def test_the_design_is_as_it_was_after_the_conversion(converted, tmp_path):
    _, instance = converted
    flat = convert_myhdl(instance, "parent", tmp_path / "flat")
    text = flat[-1].read_text()
    assert "mix_" not in text
    assert text.count("always @(posedge clk)") == 3


def myhdl_outputs() -> list[tuple[int, int]]:
    seen: list[tuple[int, int]] = []

    @block
    def bench() -> Any:
        ports = signals()
        clk, a, b, t, u = ports.values()

        @instance
        def drive() -> Any:
            for x, y in STIMULUS:
                a.next, b.next = x, y
                yield delay(1)
                clk.next = 1
                yield delay(1)
                clk.next = 0
                yield delay(1)
                seen.append((int(t.val), int(u.val)))

        return design(**ports), drive

    bench().run_sim(quiet=1)
    return seen


def test_verilator_runs_the_separate_modules_as_myhdl_simulates_the_design(converted, tmp_path):
    files, _ = converted
    steps = "".join(
        f'a = {x}; b = {y}; #1 clk = 1; #1 clk = 0; #1 $display("t=%0d u=%0d", t, u);\n'
        for x, y in STIMULUS
    )
    bench = tmp_path / "parent_tb.v"
    bench.write_text(
        "module parent_tb;\n"
        f"reg clk = 0;\nreg [{BITS - 1}:0] a = 0, b = 0;\nwire [{BITS - 1}:0] t, u;\n"
        "parent dut(.clk(clk), .a(a), .b(b), .t(t), .u(u));\n"
        f"initial begin\n{steps}$finish;\nend\nendmodule\n"
    )
    verilog = [f for f in files if f.suffix == ".v"]
    printed = run_testbench([*verilog, bench], "parent_tb", {}, {}, tmp_path / "run")
    lines = [line.split() for line in printed.splitlines() if line.startswith("t=")]
    got = [(int(t[2:]), int(u[2:])) for t, u in lines]
    assert got == myhdl_outputs()
