"""The publisher's byte packer: any number of bytes in per cycle, AXI-Stream beats out.

The mirror of the subscriber's `window`: the serializer gives 0 to W bytes per cycle (lanes
0 up of `data`), the packer appends them behind what it holds and moves the first W bytes to a
registered output beat as soon as it has them. It has `room` for W more bytes whenever it holds
at most 2W, so a serializer giving W bytes per cycle sends one beat per cycle even when what it
gives does not line up with beats.

The beat that ends a frame is known from the frame's length, loaded at `start`: once the
packer holds all the frame's remaining bytes it sends them with ``tlast`` (and ``tkeep``
marking the valid lanes). A store-and-forward publisher, which learns the length only at the
end, starts with the largest length and sends the rest on `flush`.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.ports import COUNTER_BITS
from rfc.lib.types import Instances, SignalLike


@block
def byte_packer(
    clk: SignalLike,
    rst: SignalLike,
    give: SignalLike,
    data: SignalLike,
    room: SignalLike,
    start: SignalLike,
    length: SignalLike,
    flush: SignalLike,
    idle: SignalLike,
    out: AxiStream,
    width: int,
) -> Instances:
    """Pack bytes into beats of `width` bytes.

    Args:
        clk: Clock.
        rst: Synchronous reset.
        give: Bytes given this cycle (0 to `width`), in the low lanes of `data`.
        data: The bytes.
        room: Driven: `width` bytes may be given this cycle.
        start: A frame of `length` bytes begins (only when `idle`).
        length: The frame's length.
        flush: Send what is held now, ending the frame (store-and-forward).
        idle: Driven: every byte of the last frame has left the output register.
        out: The beats; ``tlast`` marks the last beat of the frame.
        width: Bus width in bytes.
    """
    tdata, tkeep, tvalid, tready, tlast = out.signals()
    size = 3 * width
    held = Signal(intbv(0)[8 * size :])
    count = Signal(intbv(0, min=0, max=size + 1))
    remaining = Signal(intbv(0)[COUNTER_BITS:])

    @always_comb
    def status() -> None:
        room.next = count <= 2 * width
        idle.next = remaining == 0 and not tvalid

    @always_seq(clk.posedge, reset=rst)
    def pack() -> None:
        sent = 0
        if not tvalid or tready:
            last = False
            if count > 0 and remaining <= width and count >= remaining:
                sent = int(remaining)
                last = True
            elif count >= width and remaining > width:
                sent = width
            elif count > 0 and flush:
                sent = int(count)
                if count > width:
                    sent = width
                else:
                    last = True
            if sent > 0:
                beat = intbv(0)[8 * width :]
                keep = intbv(0)[width:]
                for lane in range(width):
                    if lane < sent:
                        keep[lane] = 1
                        for bit in range(8):
                            beat[8 * lane + bit] = held[8 * lane + bit]
                tdata.next = beat
                tkeep.next = keep
                tlast.next = last
            tvalid.next = sent > 0
        kept = intbv(0, min=0, max=size + 1)
        kept[:] = count - sent
        merged = intbv(0)[8 * size :]
        merged[:] = held >> (8 * sent)
        incoming = intbv(0)[8 * size :]
        for lane in range(width):
            if lane < give:
                for bit in range(8):
                    incoming[8 * lane + bit] = data[8 * lane + bit]
        held.next = merged | (incoming << (8 * int(kept)))
        count.next = kept + give
        if start:
            remaining.next = length
        elif flush and kept == 0:
            remaining.next = 0
        else:
            remaining.next = remaining - sent

    return status, pack
