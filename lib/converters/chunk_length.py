"""The declared length of a subscriber's frames, read from the PS→PL chunk headers.

The manager strips each chunk's header (docs/protocol.md: ``u16 id``, ``u16 flags``, ``u32
length``) before the payload reaches a subscriber, so a subscriber cannot know a frame's length
before its ``tlast``. `dma_tap` sits between the DMA and the manager, passes the stream through
unchanged (no register, no cycle) and holds, per subscriber it serves, the ``length`` of the
last header whose ``id`` is that subscriber's (`chunk_length`). The manager routes a chunk's
payload without buffering it, so the next header passes only after the previous chunk's last
beat was taken: the length is the current frame's when the frame's first beat is taken (the
prefix guard keeps it from then on).
"""

from __future__ import annotations

from collections.abc import Sequence

from myhdl import Signal, always_seq, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.ports import Direction, Port, PortRole, stream_path_ports
from rfc.lib.converters.wiring import follow
from rfc.lib.manager.header import HEADER_BYTES, header_assembly
from rfc.lib.types import Instances, SignalLike

#: Bits of the header's length field.
LENGTH_BITS = 32


def length_port(subscriber: int) -> str:
    """The tap's output holding the declared length of subscriber `subscriber`'s frames."""
    return f"length_sub{subscriber}"


def dma_tap_ports(width: int, subscribers: Sequence[int]) -> list[Port]:
    """The tap's ports for a bus of `width` bytes serving `subscribers`, in declaration order."""
    return stream_path_ports(width) + [
        Port(length_port(s), LENGTH_BITS, Direction.OUT, PortRole.FIELD) for s in subscribers
    ]


@block
def dma_tap(subscribers: Sequence[int], **ports: SignalLike) -> Instances:
    """The DMA stream passed on, and each subscriber's declared length; `ports`: `dma_tap_ports`."""
    s_data, s_keep, s_valid, s_ready, s_last = AxiStream.named(ports, "s_axis").signals()
    m_data, m_keep, m_valid, m_ready, m_last = AxiStream.named(ports, "m_axis").signals()
    forward = ((s_data, m_data), (s_keep, m_keep), (s_valid, m_valid), (s_last, m_last))
    through = [follow(source, target) for source, target in forward]
    through.append(follow(m_ready, s_ready))  # a plain wire both ways: no register, no cycle

    lengths = [
        chunk_length(ports["clk"], ports["rst"], ident, s_data, s_valid, m_ready, s_last,
                     ports[length_port(ident)])
        for ident in subscribers
    ]  # fmt: skip
    return through, lengths


@block
def chunk_length(
    clk: SignalLike,
    rst: SignalLike,
    ident: int,
    tdata: SignalLike,
    tvalid: SignalLike,
    tready: SignalLike,
    tlast: SignalLike,
    length: SignalLike,
) -> Instances:
    """Hold in `length` the length field of the last chunk header for subscriber `ident`.

    Every chunk starts with its header (after reset and after each ``tlast``); a header spans
    ``8 / bytes per beat`` beats.
    """
    lanes = len(tdata) // 8
    beats = max(1, HEADER_BYTES // lanes)
    beat = Signal(intbv(0, min=0, max=beats + 1))  # `beats`: in the payload
    stored = Signal(intbv(0)[8 * HEADER_BYTES :])
    word = Signal(intbv(0)[8 * HEADER_BYTES :])

    assemble = header_assembly(stored, beat, tdata, word)

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
