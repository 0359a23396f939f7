"""The declared length of a subscriber's frames, read from the PS→PL chunk headers.

The manager strips each chunk's header (docs/protocol.md: ``u16 id``, ``u16 flags``, ``u32
length``) before the payload reaches a subscriber, so a subscriber cannot know a frame's length
before its ``tlast``. This snooper watches the DMA's stream into the manager without driving
any of it and holds the ``length`` of the last header whose ``id`` is its subscriber's. The
manager routes a chunk's payload without buffering it, so the next header passes only after
the previous chunk's last beat was taken: the length is the current frame's when the frame's
first beat is taken (the prefix guard keeps it from then on).
"""

from __future__ import annotations

from typing import Any

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.ports import Direction, Port, PortRole

#: Bytes of a chunk header, and where its fields sit (docs/protocol.md).
HEADER_BYTES = 8
#: Bits of the header's length field.
LENGTH_BITS = 32
#: The prefix of the snooped DMA stream's ports.
SNOOP = "mm2s"


def snoop_ports(width: int) -> list[Port]:
    """The snooper's inputs: the DMA stream into the manager, `width` bytes a beat."""
    into = Direction.IN
    return [
        Port(f"{SNOOP}_tdata", 8 * width, into, PortRole.TDATA, SNOOP),
        Port(f"{SNOOP}_tkeep", width, into, PortRole.TKEEP, SNOOP),
        Port(f"{SNOOP}_tvalid", 1, into, PortRole.TVALID, SNOOP),
        Port(f"{SNOOP}_tready", 1, into, PortRole.TREADY, SNOOP),
        Port(f"{SNOOP}_tlast", 1, into, PortRole.TLAST, SNOOP),
    ]


@block
def chunk_length(
    clk: Any, rst: Any, ident: int, tdata: Any, tvalid: Any, tready: Any, tlast: Any, length: Any
) -> Any:
    """Hold in `length` the length field of the last chunk header for subscriber `ident`.

    Every chunk starts with its header (after reset and after each ``tlast``); a header spans
    ``8 / bytes per beat`` beats.
    """
    lanes = len(tdata) // 8
    beats = max(1, HEADER_BYTES // lanes)
    bits = 8 * lanes
    beat = Signal(intbv(0, min=0, max=beats + 1))  # `beats`: in the payload
    stored = Signal(intbv(0)[8 * HEADER_BYTES :])
    word = Signal(intbv(0)[8 * HEADER_BYTES :])

    @always_comb
    def assemble() -> None:
        assembled = intbv(0)[8 * HEADER_BYTES :]
        assembled[:] = stored
        for index in range(beats):
            if beat == index:
                assembled[(index + 1) * bits : index * bits] = tdata[bits:0]
        word.next = assembled

    @always_seq(clk.posedge, reset=rst)
    def follow() -> None:
        if tvalid and tready:
            if tlast:
                beat.next = 0
            elif beat < beats:
                beat.next = beat + 1
            if beat < beats:
                stored.next = word
            if beat == beats - 1 and word[16:0] == ident:
                length.next = word[HEADER_BYTES * 8 : HEADER_BYTES * 8 - LENGTH_BITS]

    return assemble, follow
