"""Fixture logics that stall, with the ports of the system contract, for the stall watchdog.

`deaf_top` never takes a PS→PL beat. `babbling_top` takes every PS→PL transfer, and after the
first one starts a PL→PS chunk (START, id 0) that never ends: its beats keep coming without
``tlast``. Both are top providers for ``rfc sim --top-provider``; their ``myhdl`` field gives
the same logic for ``--backend myhdl``, their ``verilog`` for Verilator.
"""

from __future__ import annotations

from functools import partial
from pathlib import Path

from myhdl import Signal, always_comb, always_seq, block

from rfc.ir.model import Design
from rfc.toolchain import convert_myhdl
from tests.runtime.echo_top import FixtureTop, contract_signals

#: The chunk header the babbling logic starts with: id 0, START, a 1 MiB message.
_HEADER = (1 << 20) << 32 | 1 << 16


@block
def stuck_logic(
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
    babble=False,
):
    width = len(m_axis_s2mm_tdata)
    started = Signal(bool(0))
    header = _HEADER & ((1 << width) - 1)
    lanes = (1 << len(m_axis_s2mm_tkeep)) - 1

    @always_comb
    def drive():
        s_axis_mm2s_tready.next = babble
        m_axis_s2mm_tvalid.next = started
        m_axis_s2mm_tdata.next = header
        m_axis_s2mm_tkeep.next = lanes
        m_axis_s2mm_tlast.next = False

    @always_seq(aclk.posedge, reset=aresetn)
    def start():
        if s_axis_mm2s_tvalid and s_axis_mm2s_tlast:
            started.next = babble

    return drive, start


def _top(design: Design, directory: Path, babble: bool) -> FixtureTop:
    width = design.project.bus_width
    name = "babbling_top" if babble else "deaf_top"
    files = convert_myhdl(
        stuck_logic(*contract_signals(width), babble=babble), name, directory,
        header="rfc test fixture: a logic that stalls",
    )  # fmt: skip
    vhdl = [f for f in files if f.suffix == ".vhd"]
    verilog = tuple(f for f in files if f.suffix == ".v")
    return FixtureTop(name, vhdl, width, partial(stuck_logic, babble=babble), verilog)


def deaf_top(design: Design, directory: Path) -> FixtureTop:
    """A logic that takes no PS→PL beat."""
    return _top(design, directory, babble=False)


def babbling_top(design: Design, directory: Path) -> FixtureTop:
    """A logic that starts a PL→PS chunk after its first input and never ends it."""
    return _top(design, directory, babble=True)
