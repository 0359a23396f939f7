"""The subscriber's byte window: AXI-Stream beats in, any number of bytes out per cycle.

A frame's fields do not respect beat boundaries once a string has shifted them, so the parser
does not read beats: it reads the first bytes of a window of up to three beats and says how
many it consumed (`take`, 0 to W). The window shifts those out, appends the next beat behind
what remains, and accepts a beat whenever at most two beats' worth are held — so a parser taking
W bytes per cycle takes one beat per cycle even when its fields straddle beats (with room for
only two beats, a misaligned stream would stall every other cycle). Bytes beyond the valid ones
are kept at zero.

A beat with ``tlast`` ends the frame: the window then accepts nothing more until the parser
`release`s it, which keeps the next frame's bytes out of this one's trailing-bytes check.
Only the last beat's ``tkeep`` is read (valid bytes from lane 0 up); other beats are full.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.types import Instances, SignalLike


@block
def byte_window(
    clk: SignalLike,
    rst: SignalLike,
    stream: AxiStream,
    take: SignalLike,
    release: SignalLike,
    front: SignalLike,
    avail: SignalLike,
    ended: SignalLike,
    width: int,
) -> Instances:
    """Buffer beats of `width` bytes; expose the first `width` bytes and how many are valid.

    Args:
        clk: Clock.
        rst: Synchronous reset.
        stream: The frame's beats; ``tkeep`` is read on the last beat only, ``tready`` is
            driven: the window accepts a beat this cycle.
        take: Bytes the parser consumes this cycle (at most `avail` and `width`).
        release: The parser finished the frame: accept the next one.
        front: Driven: the first `width` bytes (lane 0 is the next byte of the frame).
        avail: Driven: how many bytes of the window are valid (0 to 3 * width).
        ended: Driven: the frame's last beat is in the window.
        width: Bus width in bytes.
    """
    tdata, tkeep, tvalid, tready, tlast = stream.signals()
    size = 3 * width
    room = 2 * width
    buffer = Signal(intbv(0)[8 * size :])
    count = Signal(intbv(0, min=0, max=size + 1))
    done = Signal(bool(0))

    @always_comb
    def handshake() -> None:
        tready.next = count <= room and not done

    @always_comb
    def outputs() -> None:
        front.next = buffer[8 * width :]
        avail.next = count
        ended.next = done

    @always_seq(clk.posedge, reset=rst)
    def update() -> None:
        kept = intbv(0, min=0, max=size + 1)
        kept[:] = count - take
        merged = intbv(0)[8 * size :]
        merged[:] = buffer >> (8 * int(take))
        if tvalid and count <= room and not done:
            beat = intbv(0)[8 * size :]
            added = 0
            for lane in range(width):
                if tkeep[lane] or not tlast:
                    added = lane + 1
                    for bit in range(8):
                        beat[8 * lane + bit] = tdata[8 * lane + bit]
            merged[:] = merged | (beat << (8 * int(kept)))
            count.next = kept + added
            done.next = tlast
        else:
            count.next = kept
            if release:
                done.next = False
        buffer.next = merged

    return handshake, outputs, update
