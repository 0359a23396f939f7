"""PL→PS: the status chunk, in which the logic answers the processor's request for its counters.

The processor asks with an empty chunk of id `STATUS_ID` (the demultiplexer raises `request`);
`status_inserter` answers, between two chunks of the publishers, with a chunk of the same id
whose payload is every drop counter as a little-endian ``u32``, in the order of `counters`
(docs/protocol.md, "Status registers"). The counters are taken in one cycle when the answer
starts, so a reading is consistent even at 8 bits a beat. A chunk already on its way is never
cut: the answer waits for its ``tlast``, and a beat already offered to the DMA stays offered.
Between answers the publishers' stream passes through combinationally (no added latency).
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, enum, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.ports import COUNTER_BITS
from rfc.lib.manager.header import FLAG_END, FLAG_START, STATUS_ID, BusGeometry
from rfc.lib.types import Instances, SignalLike


def status_length(counters: int) -> int:
    """Payload bytes of the answer carrying `counters` counters."""
    return 4 * counters


@block
def status_inserter(
    clk: SignalLike,
    rst: SignalLike,
    request: SignalLike,
    counters: SignalLike,
    s: AxiStream,
    m: AxiStream,
    width: int,
    count: int,
) -> Instances:
    """Pass the publishers' chunks to the DMA and put a status chunk between them on request.

    Args:
        clk: Clock.
        rst: Synchronous reset, active high.
        request: bool in, high for one cycle per request.
        counters: intbv[32*count] in, counter i in bits [32*(i+1), 32*i); None when count is 0.
        s: The publishers' chunks in (from `chunk_mux`), `width` bits a beat.
        m: The stream out to the DMA (S2MM), `width` bits a beat.
        width: Bus width in bits (8, 32, 64).
        count: Number of counters (a multiple of 2, so that the chunk fills whole beats).
    """
    s_tdata, s_tkeep, s_tvalid, s_tready, s_tlast = s.signals()
    m_tdata, m_tkeep, m_tvalid, m_tready, m_tlast = m.signals()
    lanes = BusGeometry(width).lanes
    length = status_length(count)
    bits = 64 + COUNTER_BITS * count
    if (bits // 8) % lanes:
        raise ValueError(f"{count} counters do not fill whole {width}-bit beats")
    beats = bits // width
    flags = FLAG_START | FLAG_END
    t_state = enum("FORWARD", "ANSWER")  # VHDL: no process may share these names

    state = Signal(t_state.FORWARD)
    pending = Signal(bool(0))
    inside = Signal(bool(0))
    beat = Signal(intbv(0, min=0, max=max(beats, 2)))
    word = Signal(intbv(0)[bits:])
    snapshot = Signal(intbv(0)[bits:])

    # The header field by field: small constants, which every HDL reads alike.
    if count:

        @always_comb
        def assemble() -> None:
            assembled = intbv(0)[bits:]
            assembled[16:0] = STATUS_ID
            assembled[32:16] = flags
            assembled[64:32] = length
            assembled[bits:64] = counters
            snapshot.next = assembled

    else:

        @always_comb
        def assemble() -> None:
            assembled = intbv(0)[bits:]
            assembled[16:0] = STATUS_ID
            assembled[32:16] = flags
            snapshot.next = assembled

    @always_comb
    def drive_outputs() -> None:
        if state == t_state.FORWARD:
            m_tdata.next = s_tdata
            m_tkeep.next = s_tkeep
            m_tvalid.next = s_tvalid
            m_tlast.next = s_tlast
            s_tready.next = m_tready
        else:
            m_tdata.next = word[width:0]
            m_tkeep.next = 2**lanes - 1
            m_tvalid.next = 1
            m_tlast.next = beat == beats - 1
            s_tready.next = 0

    @always_seq(clk.posedge, reset=rst)
    def advance() -> None:
        wanted = pending or request
        if state == t_state.FORWARD:
            between = not inside
            if s_tvalid and m_tready:
                between = bool(s_tlast)
            inside.next = not between
            offered = s_tvalid and not m_tready  # AXI-Stream: an offered beat stays offered
            if wanted and between and not offered:
                state.next = t_state.ANSWER
                word.next = snapshot
                beat.next = 0
                wanted = False
        elif m_tready:
            word.next = word >> width
            if beat == beats - 1:
                state.next = t_state.FORWARD
            else:
                beat.next = beat + 1
        pending.next = wanted

    return assemble, drive_outputs, advance
