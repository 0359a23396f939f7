"""Plumbing shared by rfc.lib's pipelined (II = 1) blocks: stall control and stage registers.

A pipeline with one stall enable moves on every cycle its last stage is empty or its result is
taken; every register of it loads on those cycles only, so a stalled consumer holds the whole
pipeline and nothing is lost or repeated.

Ports: every handshaked block of rfc.lib's arithmetic (`rfc.lib.arith`, `rfc.lib.cordic`,
`rfc.lib.fixed`) names its clock and handshakes alike, and its docstring lists only its other
arguments:

* `clk`: the clock; `rst`: the synchronous reset (a MyHDL ``ResetSignal``);
* `in_valid` (input): the block's data inputs hold operands to take;
* `in_ready` (output): the block takes them on this cycle when `in_valid` is high;
* `out_valid` (output): the block's data outputs hold a result;
* `out_ready` (input): the consumer takes the result on this cycle;
* `advance` (input, handshake-free datapaths): the pipeline moves on this cycle;
* in a block with a `fmt` argument, its operand and result ports carry raw integers of `fmt`.
"""

from __future__ import annotations

from itertools import pairwise

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.types import Instances, SignalLike


def signed_signal(bits: int, value: int = 0) -> SignalLike:
    """A two's-complement register or wire of `bits` bits, `value` at reset."""
    return Signal(intbv(value, min=-(1 << (bits - 1)), max=1 << (bits - 1)))


@block
def stall_control(
    valid_last: SignalLike,
    out_ready: SignalLike,
    advance: SignalLike,
    in_ready: SignalLike,
    out_valid: SignalLike,
) -> Instances:
    """`advance` (and `in_ready`) when the last stage is empty or its result is being taken."""

    @always_comb
    def control() -> None:
        advance.next = out_ready or not valid_last
        in_ready.next = out_ready or not valid_last
        out_valid.next = valid_last

    return control


@block
def handshakes(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    advance: SignalLike,
    stages: int,
) -> Instances:
    """Valid/ready for a datapath of `stages` registers that moves when `advance` is high.

    The input's valid bit travels beside the data in a `delay_line`; `stall_control` drives
    `advance` from the last stage's.
    """
    valid_last = Signal(bool(0))
    valid = delay_line(clk, rst, advance, in_valid, valid_last, stages)
    control = stall_control(valid_last, out_ready, advance, in_ready, out_valid)
    return valid, control


@block
def stage_register(
    clk: SignalLike, rst: SignalLike, advance: SignalLike, source: SignalLike, target: SignalLike
) -> Instances:
    """`target` takes `source` on the cycles `advance` is high."""

    @always_seq(clk.posedge, reset=rst)
    def load() -> None:
        if advance:
            target.next = source

    return load


@block
def delay_line(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    source: SignalLike,
    target: SignalLike,
    stages: int,
) -> Instances:
    """`target` is `source` as it was `stages` advancing cycles ago (`stages` >= 1 registers).

    Each register is reset: use it for valid bits and flags. `data_delay` is the cheaper form
    for values whose validity travels beside them.
    """
    chain = [Signal(source.val) for _ in range(stages - 1)]
    taps = [source, *chain, target]
    return [stage_register(clk, rst, advance, before, after) for before, after in pairwise(taps)]


@block
def data_delay(
    clk: SignalLike, advance: SignalLike, source: SignalLike, target: SignalLike, stages: int
) -> Instances:
    """`target` is `source` as it was `stages` advancing cycles ago, in one shift register.

    Not reset (a valid bit in a `delay_line` beside it says what the values mean), so synthesis
    may put it in shift-register LUTs, and it is one process however long.
    """
    chain = [Signal(source.val) for _ in range(stages)]
    last = stages - 1

    @always_seq(clk.posedge, reset=None)
    def shift() -> None:
        if advance:
            chain[0].next = source
            for i in range(1, stages):
                chain[i].next = chain[i - 1]

    @always_comb
    def output() -> None:
        target.next = chain[last]

    return shift, output


@block
def result_queue(
    clk: SignalLike,
    rst: SignalLike,
    push: SignalLike,
    source: SignalLike,
    has_room: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    target: SignalLike,
    depth: int,
) -> Instances:
    """A small queue at a pipeline's end, so a slow consumer does not stall it every result.

    With one stall enable, a consumer that takes results late stops the whole pipeline, and
    the gaps between messages inside it stay gaps. The queue takes a result whenever the
    pipeline moves, and the pipeline moves while the queue has room (`has_room`, from the
    queue's registered fill level: the consumer's `out_ready` reaches no stage). First word
    falls through: `target` and `out_valid` show the oldest entry.

    Ports: clock and handshakes named as in this module.

    Args:
        push: Input, store `source` on this cycle.
        source: Input, the pipeline's result.
        has_room: Output, at least two entries are free: the pipeline may move this cycle.
        target: Output, as wide as `source`.
        depth: Entries (at least 2; `depth - 1` are used).
    """
    memory = [Signal(source.val) for _ in range(depth)]
    write, read = Signal(intbv(0, min=0, max=depth)), Signal(intbv(0, min=0, max=depth))
    level = Signal(intbv(0, min=0, max=depth + 1))
    last = depth - 1

    @always_seq(clk.posedge, reset=rst)
    def update() -> None:
        taken = level != 0 and out_ready
        if push:
            memory[write].next = source
            write.next = 0 if write == last else write + 1
        if taken:
            read.next = 0 if read == last else read + 1
        if push and not taken:
            level.next = level + 1
        elif taken and not push:
            level.next = level - 1

    @always_comb
    def outputs() -> None:
        target.next = memory[read]
        out_valid.next = level != 0
        has_room.next = level < last

    return update, outputs
