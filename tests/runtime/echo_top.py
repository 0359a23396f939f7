"""A fixture top-level with the ports of the system contract: pass-through logic that echoes.

Until the whole-system hardware generation (issue 7) lands, `rfc sim` is tested against this
MyHDL design. It has exactly the ports of `rfc.lower.hardware.simulation_top`'s entity and
behaves as the logic of a pass-through system: every PS→PL chunk comes back on PL→PS under the
publisher id its subscriber id routes to, cut into chunks of at most `cut_beats` payload beats
when asked (as a preemptive scheduler cuts them: START on the first, END only on a chunk known
to finish the message). Chunks of unknown ids are dropped.

`simulation_top(design, directory)` is a top provider for ``rfc sim --top-provider``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

from myhdl import ResetSignal, Signal, always_comb, always_seq, block, concat, enum, intbv

from rfc.ir.model import Design
from rfc.ir.pass_through import pass_through_routes
from rfc.toolchain import convert_myhdl

NO_ROUTE = 0xFFFF
HEADER_BITS = 64


@block
def echo_logic(
    aclk,
    aresetn,
    s_axis_mm2s_tdata,
    s_axis_mm2s_tkeep,
    s_axis_mm2s_tvalid,
    s_axis_mm2s_tready,
    s_axis_mm2s_tlast,
    m_axis_s2mm_tdata,
    m_axis_s2mm_tkeep,
    m_axis_s2mm_tvalid,
    m_axis_s2mm_tready,
    m_axis_s2mm_tlast,
    routes=(0,),
    cut_beats=0,
):
    width = len(s_axis_mm2s_tdata)
    lanes = width // 8
    header_beats = HEADER_BITS // width
    state_t = enum("IN_HEADER", "OUT_HEADER", "PAYLOAD", "DISCARD")
    state = Signal(state_t.IN_HEADER)
    header_in = Signal(intbv(0)[HEADER_BITS:])
    header_out = Signal(intbv(0)[HEADER_BITS:])
    beat = Signal(intbv(0, min=0, max=header_beats + 1))
    chunk_beats = Signal(intbv(0, min=0, max=max(cut_beats, 1) + 1))
    remaining = Signal(intbv(0)[33:])
    out_id = Signal(intbv(0)[16:])
    out_length = Signal(intbv(0)[32:])
    table = tuple(routes)
    index_bits = max(len(table) - 1, 1).bit_length()
    ident = Signal(intbv(0)[16:])
    route = Signal(intbv(0)[16:])
    index = Signal(intbv(0)[index_bits:])
    cut_bytes = cut_beats * lanes
    all_lanes = (1 << lanes) - 1

    word = Signal(intbv(0)[HEADER_BITS:])

    if width == HEADER_BITS:

        @always_comb
        def assemble():
            word.next = s_axis_mm2s_tdata

    else:

        @always_comb
        def assemble():
            word.next = concat(s_axis_mm2s_tdata, header_in[HEADER_BITS:width])

    @always_comb
    def header_word():
        ident.next = word[16:0]

    @always_comb
    def lookup_index():
        index.next = ident[index_bits:0]

    @always_comb
    def lookup():
        route.next = table[int(index)]

    @always_comb
    def handshake():
        s_axis_mm2s_tready.next = False
        m_axis_s2mm_tvalid.next = False
        m_axis_s2mm_tdata.next = header_out[width:0]
        m_axis_s2mm_tkeep.next = all_lanes
        m_axis_s2mm_tlast.next = False
        if state == state_t.IN_HEADER or state == state_t.DISCARD:
            s_axis_mm2s_tready.next = True
        elif state == state_t.OUT_HEADER:
            m_axis_s2mm_tvalid.next = True
            m_axis_s2mm_tlast.next = beat == header_beats - 1 and remaining == 0
        else:
            s_axis_mm2s_tready.next = m_axis_s2mm_tready
            m_axis_s2mm_tvalid.next = s_axis_mm2s_tvalid
            m_axis_s2mm_tdata.next = s_axis_mm2s_tdata
            m_axis_s2mm_tkeep.next = s_axis_mm2s_tkeep
            if cut_beats != 0 and chunk_beats == cut_beats - 1:
                m_axis_s2mm_tlast.next = True
            else:
                m_axis_s2mm_tlast.next = s_axis_mm2s_tlast

    @always_seq(aclk.posedge, reset=aresetn)
    def control():
        if state == state_t.IN_HEADER:
            if s_axis_mm2s_tvalid:
                header_in.next = word
                beat.next = beat + 1
                if beat == header_beats - 1:
                    beat.next = 0
                    if ident < len(table) and route != NO_ROUTE:
                        # flags: START, and END when the message fits in one chunk
                        if cut_beats == 0 or word[64:32] <= cut_bytes:
                            header_out.next = concat(word[64:32], intbv(3)[16:], route[16:])
                        else:
                            header_out.next = concat(word[64:32], intbv(1)[16:], route[16:])
                        remaining.next = word[64:32]
                        out_length.next = word[64:32]
                        out_id.next = route
                        state.next = state_t.OUT_HEADER
                    elif not s_axis_mm2s_tlast:
                        state.next = state_t.DISCARD
        elif state == state_t.OUT_HEADER:
            if m_axis_s2mm_tready:
                beat.next = beat + 1
                header_out.next = header_out >> width
                if beat == header_beats - 1:
                    beat.next = 0
                    chunk_beats.next = 0
                    if remaining == 0:
                        state.next = state_t.IN_HEADER
                    else:
                        state.next = state_t.PAYLOAD
        elif state == state_t.PAYLOAD:
            if s_axis_mm2s_tvalid and m_axis_s2mm_tready:
                if cut_beats != 0:
                    chunk_beats.next = chunk_beats + 1
                if remaining > lanes:
                    remaining.next = remaining - lanes
                else:
                    remaining.next = 0
                if s_axis_mm2s_tlast:
                    state.next = state_t.IN_HEADER
                elif cut_beats != 0 and chunk_beats == cut_beats - 1:
                    # a continuation: END only when the rest fits in one chunk
                    if remaining - lanes <= cut_bytes:
                        header_out.next = concat(out_length, intbv(2)[16:], out_id)
                    else:
                        header_out.next = concat(out_length, intbv(0)[16:], out_id)
                    state.next = state_t.OUT_HEADER
        elif state == state_t.DISCARD and s_axis_mm2s_tvalid and s_axis_mm2s_tlast:
            state.next = state_t.IN_HEADER

    return assemble, header_word, lookup_index, lookup, handshake, control


def contract_signals(width: int) -> list:
    """Fresh signals for the contract's ports, in their order: clock, reset, PS→PL, PL→PS."""
    lanes = width // 8
    streams = [
        signal
        for _ in range(2)
        for signal in (
            Signal(intbv(0)[width:]),
            Signal(intbv(0)[lanes:]),
            *(Signal(bool(0)) for _ in range(3)),
        )
    ]
    return [Signal(bool(0)), ResetSignal(0, active=0, isasync=False), *streams]


def echo_instance(width: int, routes: tuple[int, ...], cut_beats: int = 0):
    """Elaborate the fixture with fresh signals (named as the contract's ports)."""
    return echo_logic(*contract_signals(width), routes=routes, cut_beats=cut_beats)


@dataclass(frozen=True)
class FixtureTop:
    """What `rfc.lower.hardware.simulation_top` returns: entity, VHDL sources, bus width.

    `myhdl` makes the same logic as a MyHDL block from the port signals (``--backend myhdl``);
    `verilog`, when given, is the same logic for Verilator.
    """

    top: str
    sources: list[Path]
    bus_width: int
    myhdl: Callable[..., Any]
    verilog: tuple[Path, ...] = ()


def route_table(design: Design) -> tuple[int, ...]:
    """Publisher id per subscriber id of a pass-through design (NO_ROUTE where none)."""
    routes = pass_through_routes(design)
    size = max(routes, default=0) + 1
    return tuple(routes.get(i, NO_ROUTE) for i in range(size))


def simulation_top(design: Design, directory: Path, cut_beats: int = 3) -> FixtureTop:
    """Convert the echo logic of a pass-through design to VHDL in `directory`."""
    width = design.project.bus_width
    name = "echo_top"
    routes = route_table(design)
    files = convert_myhdl(
        echo_instance(width, routes, cut_beats),
        name,
        directory,
        verilog=False,
        header="rfc test fixture: pass-through logic",
    )
    return FixtureTop(name, files, width, partial(echo_logic, routes=routes, cut_beats=cut_beats))
