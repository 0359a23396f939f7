"""PS→PL: read each chunk's header and route its payload to the subscriber the id names.

The payload passes through combinationally (no added latency, one beat per cycle). Chunks that
break the protocol — a header cut short by `tlast` or with bytes missing from its beats, an id
without a subscriber, flags other than START|END, a payload whose byte count differs from the
header's length — are counted in `error_count`; a chunk with a bad header is consumed and
dropped up to its `tlast`, so the next chunk starts clean. A zero-length message (a ROS 1
message without fields) reaches its subscriber as one null beat: `tkeep` all zero with `tlast`.
An empty chunk of id `STATUS_ID` is the processor asking for the drop counters: it raises
`status_request` for one cycle (`rfc.lib.manager.status` answers it).
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, enum, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.manager.header import (
    FLAG_END,
    FLAG_START,
    HEADER_BYTES,
    STATUS_ID,
    BusGeometry,
    header_assembly,
)
from rfc.lib.types import Instances, SignalLike

#: Width of the saturating protocol-error counter.
ERROR_COUNT_BITS = 16


@block
def chunk_demux(
    clk: SignalLike,
    rst: SignalLike,
    s: AxiStream,
    m: AxiStream,
    error_count: SignalLike,
    width: int,
    subscribers: int,
    status_request: SignalLike = None,
) -> Instances:
    """Demultiplex PS→PL chunks to `subscribers` converters.

    Args:
        clk: Clock.
        rst: Synchronous reset, active high.
        s: The stream in from the DMA (MM2S), `width` bits a beat.
        m: The payloads out: ``tdata``, ``tkeep`` and ``tlast`` shared by every subscriber,
            ``tvalid`` and ``tready`` one bit per subscriber.
        error_count: intbv[16] out, protocol errors seen (saturating).
        width: Bus width in bits (8, 32, 64).
        subscribers: Number of subscriber converters (≥ 1).
        status_request: bool out, high for one cycle after a status request chunk (None
            when nothing answers requests).
    """
    s_tdata, s_tkeep, s_tvalid, s_tready, s_tlast = s.signals()
    m_tdata, m_tkeep, m_tvalid, m_tready, m_tlast = m.signals()
    geometry = BusGeometry(width)
    lanes = geometry.lanes
    header_beats = geometry.header_beats
    last_header_beat = header_beats - 1
    whole = FLAG_START | FLAG_END
    full = 2**lanes - 1
    popcounts = tuple(bin(keep).count("1") for keep in range(2**lanes))
    t_state = enum("HEADER", "ROUTE", "DROP", "EMPTY")  # VHDL: no process may share these names

    state = Signal(t_state.HEADER)
    beat = Signal(intbv(0, min=0, max=max(header_beats, 2)))
    stored = Signal(intbv(0)[8 * HEADER_BYTES :])
    word = Signal(intbv(0)[8 * HEADER_BYTES :])
    target = Signal(intbv(0, min=0, max=max(subscribers, 2)))
    left = Signal(intbv(0)[33:])  # payload bytes the header announced and no beat brought yet
    beat_bytes = Signal(intbv(0, min=0, max=lanes + 1))
    errors = Signal(intbv(0)[ERROR_COUNT_BITS:])
    faulted = Signal(bool(0))  # counted a cycle later, so the check and the count run apart
    asked = Signal(bool(0))
    answering = status_request is not None

    assemble_header = header_assembly(stored, beat, s_tdata, word)

    @always_comb
    def count_lanes() -> None:
        # A table of every tkeep (two levels of LUTs), not a chain of adders.
        beat_bytes.next = popcounts[s_tkeep]

    @always_comb
    def drive_outputs() -> None:
        m_tdata.next = s_tdata
        if state == t_state.EMPTY:
            m_tkeep.next = 0
            m_tlast.next = 1
        else:
            m_tkeep.next = s_tkeep
            m_tlast.next = s_tlast
        valid = intbv(0)[subscribers:]
        for index in range(subscribers):
            if target == index:
                if state == t_state.ROUTE:
                    valid[index] = s_tvalid
                elif state == t_state.EMPTY:
                    valid[index] = 1
        m_tvalid.next = valid
        if state == t_state.ROUTE:
            s_tready.next = m_tready[target]
        elif state == t_state.EMPTY:
            s_tready.next = 0
        else:
            s_tready.next = 1

    @always_comb
    def report() -> None:
        error_count.next = errors

    if answering:

        @always_comb
        def ask() -> None:
            status_request.next = asked

    @always_seq(clk.posedge, reset=rst)
    def parse() -> None:
        fault = False
        asked.next = False
        if state == t_state.HEADER:
            if s_tvalid and s_tkeep != full:
                # Header bytes missing: a truncated chunk.
                fault = True
                stored.next = 0
                beat.next = 0
                if not s_tlast:
                    state.next = t_state.DROP
            elif s_tvalid:
                if beat == last_header_beat:
                    stored.next = 0
                    beat.next = 0
                    left.next = word[64:32]
                    good = word[16:0] < subscribers and word[32:16] == whole
                    if good:
                        target.next = word[16:0]
                    if s_tlast:
                        # A chunk of header only: fine for an empty message.
                        if good and word[64:32] == 0:
                            state.next = t_state.EMPTY
                        elif word[16:0] == STATUS_ID and word[32:16] == whole and word[64:32] == 0:
                            asked.next = True
                        else:
                            fault = True
                    elif good:
                        state.next = t_state.ROUTE
                    else:
                        fault = True
                        state.next = t_state.DROP
                elif s_tlast:
                    fault = True
                    stored.next = 0
                    beat.next = 0
                else:
                    stored.next = word
                    beat.next = beat + 1
        elif state == t_state.ROUTE:
            if s_tvalid and m_tready[target]:
                if s_tlast:
                    state.next = t_state.HEADER
                    if left != beat_bytes:
                        fault = True
                else:
                    left.next = left - beat_bytes
        elif state == t_state.DROP:
            if s_tvalid and s_tlast:
                state.next = t_state.HEADER
        elif m_tready[target]:
            state.next = t_state.HEADER
        faulted.next = fault
        if faulted and errors != 2**ERROR_COUNT_BITS - 1:
            errors.next = errors + 1

    if answering:
        return assemble_header, count_lanes, drive_outputs, report, ask, parse
    return assemble_header, count_lanes, drive_outputs, report, parse
