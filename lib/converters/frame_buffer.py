"""The store-and-forward publisher's frame buffer: a whole frame in, then out with its length.

When a frame's length depends on what is inside its sequences' elements (`Plan.
store_and_forward`), the publisher serializes the frame into this buffer, counting its bytes,
and `commit`s it with that length; only then does the buffer send it. A frame longer than the
buffer is dropped at commit and counted in `errors`.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.ports import COUNTER_BITS
from rfc.lib.types import Instances, SignalLike


@block
def frame_buffer(
    clk: SignalLike,
    rst: SignalLike,
    w_data: SignalLike,
    w_valid: SignalLike,
    commit: SignalLike,
    length: SignalLike,
    busy: SignalLike,
    errors: SignalLike,
    out: AxiStream,
    width: int,
    depth: int,
) -> Instances:
    """Buffer one frame of up to `depth` beats of `width` bytes.

    Args:
        clk: Clock.
        rst: Synchronous reset.
        w_data: A beat of the frame being written (always accepted).
        w_valid: `w_data` is valid.
        commit: The frame is complete and `length` bytes long: send it.
        length: Its length in bytes.
        busy: Driven: a committed frame is being sent; nothing may be written.
        errors: Driven: frames dropped for not fitting.
        out: The frame's beats.
        width: Bus width in bytes.
        depth: Beats the buffer holds.
    """
    tdata, tkeep, tvalid, tready, tlast = out.signals()
    memory = [Signal(intbv(0)[8 * width :]) for _ in range(depth)]
    written = Signal(intbv(0, min=0, max=depth + 1))
    read = Signal(intbv(0, min=0, max=depth + 1))
    left = Signal(intbv(0)[COUNTER_BITS:])
    sending = Signal(bool(0))
    overflow = Signal(bool(0))
    dropped = Signal(intbv(0)[COUNTER_BITS:])

    @always_comb
    def status() -> None:
        busy.next = sending
        errors.next = dropped

    @always_seq(clk.posedge, reset=None)
    def store() -> None:
        if w_valid and not sending and written < depth:
            memory[written].next = w_data

    @always_seq(clk.posedge, reset=rst)
    def control() -> None:
        if commit:
            if overflow:
                dropped.next = dropped + 1
                written.next = 0
                overflow.next = False
            else:
                sending.next = True
                left.next = length
                read.next = 0
        elif w_valid and not sending:
            if written < depth:
                written.next = written + 1
            else:
                overflow.next = True
        if sending and (not tvalid or tready):
            if left > 0:
                tdata.next = memory[read]
                keep = intbv(0)[width:]
                for lane in range(width):
                    keep[lane] = lane < left
                tkeep.next = keep
                tlast.next = left <= width
                tvalid.next = True
                if left > width:  # the last beat leaves `read` on a word of the memory
                    read.next = read + 1
                    left.next = left - width
                else:
                    left.next = 0
            else:
                tvalid.next = False
                sending.next = False
                written.next = 0
        elif tready:
            tvalid.next = False

    return status, store, control
