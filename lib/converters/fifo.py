"""A synchronous FIFO with valid/ready on both sides (first word falls through).

The words sit in a `ram` (block RAM in the FPGA); one output register in front of it makes the
oldest word visible with `out_valid` without a read request, and keeps one word per cycle
flowing under a continuous `out_ready`.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.ram import ram
from rfc.lib.types import Instances, SignalLike


@block
def fifo(
    clk: SignalLike,
    rst: SignalLike,
    in_data: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    out_data: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    depth: int,
) -> Instances:
    """Hold `depth` + 1 words of `len(in_data)` bits; a word written shows two cycles later."""
    depth = max(depth, 2)  # an address needs a bit
    width = len(in_data)
    head = Signal(intbv(0, min=0, max=depth))
    tail = Signal(intbv(0, min=0, max=depth))
    count = Signal(intbv(0, min=0, max=depth + 1))
    push, fetch, shown = (Signal(bool(0)) for _ in range(3))
    word, data = (Signal(intbv(0)[width:]) for _ in range(2))
    last = depth - 1

    @always_comb
    def control() -> None:
        data.next = in_data  # a plain signal: the RAM's VHDL cannot take a MyHDL shadow signal
        push.next = in_valid and count < depth
        fetch.next = count > 0 and (not shown or out_ready)

    @always_comb
    def status() -> None:
        in_ready.next = count < depth
        out_valid.next = shown
        out_data.next = word

    @always_seq(clk.posedge, reset=rst)
    def pointers() -> None:
        if push:
            if tail == last:
                tail.next = 0
            else:
                tail.next = tail + 1
        if fetch:
            if head == last:
                head.next = 0
            else:
                head.next = head + 1
            shown.next = True
        elif out_ready:
            shown.next = False
        if push and not fetch:
            count.next = count + 1
        elif fetch and not push:
            count.next = count - 1

    storage = ram(clk, push, tail, data, fetch, head, word, depth)
    return control, status, pointers, storage
