"""The chunk header as the manager's hardware sees it: byte lanes of a 64-bit word."""

from __future__ import annotations

from dataclasses import dataclass

from myhdl import always_comb, block, intbv

from rfc.lib.types import Instances, SignalLike

#: Bytes of a chunk header: u16 id, u16 flags, u32 length (little-endian).
HEADER_BYTES = 8
#: Flag bits of the header.
FLAG_START = 1
FLAG_END = 2
#: The id of the status chunks (docs/protocol.md): the PS asks with an empty one, the logic
#: answers with one holding its drop counters. Subscriber and publisher ids stay below it.
STATUS_ID = 0xFFFF

BUS_WIDTHS = (8, 32, 64)


@dataclass(frozen=True)
class BusGeometry:
    """How a header and a payload fall on beats of a bus width.

    Attributes:
        width: Bits per beat (8, 32 or 64).
    """

    width: int

    def __post_init__(self) -> None:
        if self.width not in BUS_WIDTHS:
            raise ValueError(f"bus width must be one of {BUS_WIDTHS}, not {self.width}")

    @property
    def lanes(self) -> int:
        """Bytes per beat (also the width of `tkeep`)."""
        return self.width // 8

    @property
    def header_beats(self) -> int:
        """Beats the 8-byte header takes; the payload starts on the next beat."""
        return HEADER_BYTES // self.lanes


def header_word(ident: int, flags: int, length: int) -> int:
    """The 64-bit little-endian header as an integer (byte 0 in bits 7..0)."""
    return ident | (flags << 16) | (length << 32)


@block
def header_assembly(
    stored: SignalLike, beat: SignalLike, data: SignalLike, word: SignalLike
) -> Instances:
    """`word`: the header bytes `stored` so far, with this beat's `data` in place `beat`.

    A header of `HEADER_BYTES` spans ``8 * HEADER_BYTES / len(data)`` beats (at least one);
    whoever reads a header (the demultiplexer, a subscriber's length tap) keeps `stored` itself.
    """
    bits = len(data)
    beats = max(1, 8 * HEADER_BYTES // bits)

    @always_comb
    def assemble() -> None:
        assembled = intbv(0)[8 * HEADER_BYTES :]
        assembled[:] = stored
        for index in range(beats):
            if beat == index:
                assembled[(index + 1) * bits : index * bits] = data
        word.next = assembled

    return assemble
