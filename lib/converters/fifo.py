"""A synchronous FIFO with valid/ready on both sides (first word falls through)."""

from __future__ import annotations

from typing import Any

from myhdl import Signal, always_comb, always_seq, block, intbv


@block
def fifo(
    clk: Any,
    rst: Any,
    in_data: Any,
    in_valid: Any,
    in_ready: Any,
    out_data: Any,
    out_valid: Any,
    out_ready: Any,
    depth: int,
) -> Any:
    """Hold up to `depth` words of `len(in_data)` bits; a word written is readable next cycle."""
    width = len(in_data)
    memory = [Signal(intbv(0)[width:]) for _ in range(depth)]
    head = Signal(intbv(0, min=0, max=depth))
    tail = Signal(intbv(0, min=0, max=depth))
    count = Signal(intbv(0, min=0, max=depth + 1))
    last = depth - 1

    @always_comb
    def status() -> None:
        in_ready.next = count < depth
        out_valid.next = count > 0

    @always_comb
    def front() -> None:
        out_data.next = memory[head]

    @always_seq(clk.posedge, reset=None)
    def write() -> None:
        if in_valid and count < depth:
            memory[tail].next = in_data

    @always_seq(clk.posedge, reset=rst)
    def pointers() -> None:
        push = in_valid and count < depth
        pop = out_ready and count > 0
        if push:
            if tail == last:
                tail.next = 0
            else:
                tail.next = tail + 1
        if pop:
            if head == last:
                head.next = 0
            else:
                head.next = head + 1
        if push and not pop:
            count.next = count + 1
        elif pop and not push:
            count.next = count - 1

    return status, front, write, pointers
