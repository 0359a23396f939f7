"""tools/check_hdl_equivalence.py proves a relabelled block equal to its old self, and no other.

The oracle is Yosys' equivalence checker on GHDL's synthesis; these tests make sure the tool
asks it the right question: a change of labels and of how a condition is written is proved, a
change of behaviour is not, and GHDL's numbered nets are never taken for the same signal.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from myhdl import ResetSignal, Signal, always_comb, always_seq, block, intbv

ROOT = Path(__file__).resolve().parents[2]


def load_tool():
    path = ROOT / "tools" / "check_hdl_equivalence.py"
    spec = importlib.util.spec_from_file_location("check_hdl_equivalence", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


TOOL = load_tool()


@block
def counter(clk, rst, enable, limit, count, at_limit):
    """Counts while enabled, wrapping at `limit`."""

    @always_seq(clk.posedge, reset=rst)
    def step():
        if enable and count != limit:
            count.next = count + 1
        elif enable:
            count.next = 0

    @always_comb
    def flag():
        at_limit.next = count == limit

    return step, flag


@block
def counter_relabelled(clk, rst, enable, limit, count, at_limit):
    """`counter` with other process labels and its conditions written another way."""

    @always_seq(clk.posedge, reset=rst)
    def advance():
        if not (not enable or count == limit):
            count.next = count + 1
        elif enable:
            count.next = 0

    @always_comb
    def compare():
        at_limit.next = limit == count

    return advance, compare


@block
def counter_saturating(clk, rst, enable, limit, count, at_limit):
    """`counter` that stays at `limit` instead of wrapping: another circuit."""

    @always_seq(clk.posedge, reset=rst)
    def step():
        if enable and count != limit:
            count.next = count + 1

    @always_comb
    def flag():
        at_limit.next = count == limit

    return step, flag


def convert(design, folder: Path) -> None:
    clk, rst = Signal(bool(0)), ResetSignal(0, active=1, isasync=False)
    ports = (Signal(bool(0)), Signal(intbv(0)[8:]), Signal(intbv(0)[8:]), Signal(bool(0)))
    folder.mkdir(parents=True)
    design(clk, rst, *ports).convert(
        hdl="VHDL", path=str(folder), name="unit", no_myhdl_header=True
    )


def verdicts(tmp_path: Path, gate) -> list:
    convert(counter, tmp_path / "before")
    convert(gate, tmp_path / "after")
    return TOOL.compare("unit", tmp_path / "before", tmp_path / "after", tmp_path / "work")


def test_relabelled_processes_and_rewritten_conditions_are_proved_the_same_circuit(tmp_path):
    (verdict,) = verdicts(tmp_path, counter_relabelled)
    assert verdict.file == "unit.vhd"
    assert verdict.proved, verdict.detail


def test_a_changed_behaviour_is_not_proved(tmp_path):
    (verdict,) = verdicts(tmp_path, counter_saturating)
    assert not verdict.proved
    assert "unproved" in verdict.detail


def test_identical_text_needs_no_proof(tmp_path):
    assert verdicts(tmp_path, counter) == []
