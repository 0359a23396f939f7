"""Vivado scripts: the block design drawn from the netlist, checked under recording stand-ins."""

from __future__ import annotations

from pathlib import Path

import pytest
from myhdl import ResetSignal, Signal, always_comb, block, intbv

from rfc.lib.converters.ports import Direction
from rfc.lower.block_design import block_design
from rfc.lower.netlist import EntityDecl, Netlist, NetlistError, PortDecl, constant
from rfc.lower.vivado import VivadoProject, vivado_artifacts
from rfc.toolchain import convert_myhdl, start_new_design
from tests.support.vendor_check import check_vivado, run_script

WIDTH = 64


@block
def echo(
    clk,
    rst,
    enable,
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
    seen,
):
    """Streams MM2S back to S2MM when enabled; `seen` is an output nobody reads."""

    @always_comb
    def loop():
        m_axis_s2mm_tdata.next = s_axis_mm2s_tdata
        m_axis_s2mm_tkeep.next = s_axis_mm2s_tkeep
        m_axis_s2mm_tvalid.next = s_axis_mm2s_tvalid and enable
        m_axis_s2mm_tlast.next = s_axis_mm2s_tlast
        s_axis_mm2s_tready.next = m_axis_s2mm_tready and enable
        seen.next = s_axis_mm2s_tvalid

    return loop


def _stream(prefix, mode_in):
    into, out = (Direction.IN, Direction.OUT) if mode_in else (Direction.OUT, Direction.IN)
    return (
        PortDecl(f"{prefix}_tdata", into, WIDTH),
        PortDecl(f"{prefix}_tkeep", into, WIDTH // 8),
        PortDecl(f"{prefix}_tvalid", into, 1, wire=True),
        PortDecl(f"{prefix}_tready", out, 1, wire=True),
        PortDecl(f"{prefix}_tlast", into, 1, wire=True),
    )


ECHO = EntityDecl(
    "echo",
    (
        PortDecl("clk", Direction.IN, 1, wire=True),
        PortDecl("rst", Direction.IN, 1, wire=True),
        PortDecl("enable", Direction.IN, 1, wire=True),
        *_stream("s_axis_mm2s", True),
        *_stream("m_axis_s2mm", False),
        PortDecl("seen", Direction.OUT, 1, wire=True),
    ),
)


def system_netlist():
    top = Netlist(
        EntityDecl(
            "system_pl",
            (
                PortDecl("aclk", Direction.IN, 1, wire=True),
                PortDecl("aresetn", Direction.IN, 1, wire=True),
                *_stream("s_axis_mm2s", True),
                *_stream("m_axis_s2mm", False),
            ),
        )
    )
    rst = top.signal("rst", wire=True)
    top.assign(rst, "not aresetn")
    connections = {p.name: top.port(p.name) for p in ECHO.ports if "axis" in p.name}
    connections |= {
        "clk": top.port("aclk"),
        "rst": rst,
        "enable": constant(1, 1, True),
        "seen": None,
    }
    top.instance("echo_0", ECHO, connections)
    return top


def write_build(tmp_path: Path, design) -> Path:
    start_new_design()
    signals = [Signal(intbv(0)[p.bits :]) if not p.wire else Signal(bool(0)) for p in ECHO.ports]
    signals[1] = ResetSignal(0, active=1, isasync=False)
    hdl = convert_myhdl(echo(*signals), "echo", tmp_path / "hw", verilog=False)
    project = VivadoProject(
        "EchoSystem",
        "xc7z020clg400-1",
        WIDTH,
        100.0,
        False,
        tuple(str(p.relative_to(tmp_path)) for p in hdl),
    )
    for artifact in vivado_artifacts(project, design):
        path = tmp_path / artifact.path
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(artifact.text)
    return tmp_path / "vivado" / "build.tcl"


def test_block_design_follows_the_netlist():
    design = block_design(system_netlist())
    assert design.cells == (("echo_0", "echo"),)
    assert design.clock_pins == ("echo_0/clk",)
    assert design.reset_pins == ("echo_0/rst",)
    assert design.constants == (("const_0", 1, 1),)
    assert design.nets == (("const_0_net", ("const_0/dout", "echo_0/enable")),)
    assert (design.dma_mm2s, design.dma_s2mm) == ("echo_0/s_axis_mm2s", "echo_0/m_axis_s2mm")


def test_a_top_level_output_only_one_cell_drives_is_left_out_of_the_block_design():
    top = system_netlist()
    status = Netlist(
        EntityDecl("system_pl", (*top.entity.ports, PortDecl("status", Direction.OUT, 1, True)))
    )
    rst = status.signal("rst", wire=True)
    status.assign(rst, "not aresetn")
    connections = {p.name: status.port(p.name) for p in ECHO.ports if "axis" in p.name}
    connections |= {"clk": status.port("aclk"), "rst": rst, "enable": constant(1, 1, True)}
    status.instance("echo_0", ECHO, connections | {"seen": status.port("status")})
    design = block_design(status)
    assert design.nets == block_design(top).nets  # no net of the lone pin echo_0/seen


def test_vivado_script_runs_under_the_stand_ins(tmp_path):
    script = write_build(tmp_path, block_design(system_netlist()))
    record = run_script(script, tmp_path / "vivado.log")
    generated = check_vivado(record)
    assert set(generated) == {"echo_0"}
    assert record.of("write_hw_platform")
    ((part,),) = [args[3] for args in record.of("create_project")]
    assert part == "xc7z020clg400-1"


def test_the_check_catches_an_unconnected_input(tmp_path):
    design = block_design(system_netlist())
    broken = design.__class__(**{**design.__dict__, "constants": (), "nets": ()})
    script = write_build(tmp_path, broken)
    with pytest.raises(AssertionError, match="input echo_0/enable is not connected"):
        check_vivado(run_script(script, tmp_path / "vivado.log"))


def test_sliced_nets_have_no_block_design_form():
    top = system_netlist()
    wide = top.signal("wide", 2)
    top.assign(wide, constant(0, 2))
    with pytest.raises(NetlistError, match="has no block-design form"):
        block_design(top)
