"""Small MyHDL blocks both converters use to select and track handshakes."""

from __future__ import annotations

from dataclasses import dataclass

from myhdl import ConcatSignal, always_comb, always_seq, block

from rfc.lib.converters.steps import Loop, Plan
from rfc.lib.types import Instances, SignalLike


def bits_of(signals: list[SignalLike]) -> SignalLike:
    """One vector of single-bit signals, the first in bit 0."""
    return ConcatSignal(*reversed(signals)) if len(signals) > 1 else signals[0]


@block
def select_bit(
    bits: SignalLike, table: tuple[int, ...], pc: SignalLike, out: SignalLike
) -> Instances:
    """Drive `out` with bit ``table[pc]`` of `bits` (the handshake of the current step)."""

    @always_comb
    def select() -> None:
        index = table[pc]
        out.next = bits[index]

    return select


@block
def index_bit(bits: SignalLike, index: SignalLike | int, out: SignalLike) -> Instances:
    """Drive `out` with bit `index` of `bits` (a signal, or a constant bit position)."""

    @always_comb
    def select() -> None:
        out.next = bits[index]

    return select


@block
def follow(source: SignalLike, target: SignalLike) -> Instances:
    """Drive `target` with `source`."""

    @always_comb
    def copy() -> None:
        target.next = source

    return copy


@dataclass(frozen=True)
class LoopControl:
    """The signals of a converter's control that every loop counter reads.

    Attributes:
        clk: Clock.
        rst: Synchronous reset.
        pc: The current step.
        count: The element count a Loop step loads.
        load: The control loads `count` at the current (Loop) step.
        step: The control finishes an element at the current (Next) step.
    """

    clk: SignalLike
    rst: SignalLike
    pc: SignalLike
    count: SignalLike
    load: SignalLike
    step: SignalLike

    def signals(self) -> tuple[SignalLike, ...]:
        """clk, rst, pc, count, load, step: to bind to a block's local names."""
        return self.clk, self.rst, self.pc, self.count, self.load, self.step


@block
def loop_counter(
    control: LoopControl, at: int, end: int, counter: SignalLike, more: SignalLike
) -> Instances:
    """Elements left in one sequence: loaded at its Loop step, counted down at its Next."""
    clk, rst, pc, count, load, step = control.signals()

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
def loop_counters(
    plan: Plan,
    control: LoopControl,
    counters: list[SignalLike],
    mores: list[SignalLike],
    more: SignalLike,
) -> Instances:
    """One `loop_counter` per Loop step; `more` tells whether the current loop repeats."""
    loops = [at for at, step in enumerate(plan.steps) if isinstance(step, Loop)]
    blocks = []
    for at, counter, flag in zip(loops, counters, mores, strict=True):
        loop = plan.loop(at)
        blocks.append(loop_counter(control, at, loop.next, counter, flag))
    if len(mores) > 1:
        table = [0] * len(plan.steps)
        for index, at in enumerate(loops):
            table[plan.loop(at).next] = index
        blocks.append(select_bit(bits_of(mores), tuple(table), control.pc, more))
    elif mores:
        blocks.append(follow(mores[0], more))
    return blocks
