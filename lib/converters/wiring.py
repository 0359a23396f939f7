"""Small MyHDL blocks both converters use to select and track handshakes."""

from __future__ import annotations

from typing import Any

from myhdl import ConcatSignal, always_comb, always_seq, block

from rfc.lib.converters.steps import Loop, Plan


def bits_of(signals: list[Any]) -> Any:
    """One vector of single-bit signals, the first in bit 0."""
    return ConcatSignal(*reversed(signals)) if len(signals) > 1 else signals[0]


@block
def select_bit(bits: Any, table: tuple[int, ...], pc: Any, out: Any) -> Any:
    """Drive `out` with bit ``table[pc]`` of `bits` (the handshake of the current step)."""

    @always_comb
    def select() -> None:
        index = table[pc]
        out.next = bits[index]

    return select


@block
def index_bit(bits: Any, index: Any, out: Any) -> Any:
    """Drive `out` with bit `index` of `bits`."""

    @always_comb
    def select() -> None:
        out.next = bits[index]

    return select


@block
def follow(source: Any, target: Any) -> Any:
    """Drive `target` with `source`."""

    @always_comb
    def copy() -> None:
        target.next = source

    return copy


@block
def loop_counter(clk: Any, rst: Any, pc: Any, count: Any, load: Any, step: Any, at: int,
                 end: int, counter: Any, more: Any) -> Any:  # fmt: skip
    """Elements left in one sequence: loaded at its Loop step, counted down at its Next."""

    @always_seq(clk.posedge, reset=rst)
    def track() -> None:
        if load and pc == at:
            counter.next = count[len(counter) :]
        elif step and pc == end:
            counter.next = counter - 1

    @always_comb
    def status() -> None:
        more.next = counter > 1

    return track, status


@block
def loop_counters(plan: Plan, clk: Any, rst: Any, pc: Any, count: Any, load: Any, step: Any,
                  counters: list[Any], mores: list[Any], more: Any) -> Any:  # fmt: skip
    """One `loop_counter` per Loop step; `more` tells whether the current loop repeats."""
    loops = [at for at, step in enumerate(plan.steps) if isinstance(step, Loop)]
    blocks = []
    for at, counter, flag in zip(loops, counters, mores, strict=True):
        loop = plan.loop(at)
        blocks.append(loop_counter(clk, rst, pc, count, load, step, at, loop.next, counter, flag))
    if len(mores) > 1:
        table = [0] * len(plan.steps)
        for index, at in enumerate(loops):
            table[plan.loop(at).next] = index
        blocks.append(select_bit(bits_of(mores), tuple(table), pc, more))
    elif mores:
        blocks.append(follow(mores[0], more))
    return blocks
