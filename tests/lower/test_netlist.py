"""The structural VHDL builder: checked wiring, and output GHDL accepts."""

from __future__ import annotations

import json
import subprocess

import pytest

from rfc.lib.converters.ports import Direction
from rfc.lower.netlist import EntityDecl, Netlist, NetlistError, PortDecl, constant
from rfc.toolchain import analyze, convert_myhdl, start_new_design
from tests.toolchain.counter import counter_instance

COUNTER = EntityDecl(
    "counter8",
    (
        PortDecl("clk", Direction.IN, 1, wire=True),
        PortDecl("rst", Direction.IN, 1, wire=True),
        PortDecl("enable", Direction.IN, 1, wire=True),
        PortDecl("count", Direction.OUT, 8),
    ),
)


def two_counters():
    top = Netlist(
        EntityDecl(
            "pair",
            (
                PortDecl("clk", Direction.IN, 1, wire=True),
                PortDecl("resetn", Direction.IN, 1, wire=True),
                PortDecl("counts", Direction.OUT, 16),
            ),
        ),
        comment="two counters side by side",
    )
    rst = top.signal("rst", wire=True)
    top.assign(rst, "not resetn")
    counts = top.port("counts")
    for index in range(2):
        top.instance(
            f"counter_{index}",
            COUNTER,
            {
                "clk": top.port("clk"),
                "rst": rst,
                "enable": constant(1, 1, wire=True),
                "count": counts.slice(8 * index + 7, 8 * index),
            },
        )
    return top


def test_rendered_netlist_elaborates_in_ghdl(tmp_path):
    start_new_design()
    files = convert_myhdl(counter_instance(), "counter8", tmp_path, verilog=False)
    top = tmp_path / "pair.vhd"
    top.write_text(two_counters().render())
    analyze([*files, top], tmp_path / "work", top="pair")
    assert top.read_text().startswith("-- two counters side by side\n")


def test_every_port_must_be_named():
    top = two_counters()
    with pytest.raises(NetlistError, match="port enable of counter8 is not connected"):
        top.instance("c", COUNTER, {"clk": top.port("clk"), "rst": top.port("clk")})


def test_widths_and_kinds_must_agree():
    top = two_counters()
    spare = top.signal("spare", 4)
    with pytest.raises(NetlistError, match=r"std_logic_vector\(7 downto 0\) port connected"):
        top.instance(
            "c",
            COUNTER,
            {
                "clk": top.port("clk"),
                "rst": top.port("clk"),
                "enable": top.port("clk"),
                "count": spare,
            },
        )


def test_two_drivers_and_undriven_bits_are_refused():
    top = two_counters()
    top.assign(top.port("counts").slice(3, 0), constant(0, 4))
    with pytest.raises(NetlistError, match=r"counts\(0\) driven by counter_0.count and"):
        top.check()
    lonely = Netlist(EntityDecl("lonely", (PortDecl("o", Direction.OUT, 2),)))
    with pytest.raises(NetlistError, match=r"o\(0\) has no driver"):
        lonely.render()


def test_inputs_cannot_be_left_open():
    top = two_counters()
    with pytest.raises(NetlistError, match="input clk must be driven"):
        top.instance("c", COUNTER, {"clk": None, "rst": None, "enable": None, "count": None})


def yosys_ports(files: list, top: str, workdir) -> dict:
    """The ports of `top` as Yosys elaborates the Verilog: name → (direction, bits)."""
    out = workdir / "design.json"
    script = f"read_verilog {' '.join(map(str, files))}; hierarchy -check -top {top}; proc; "
    script += f"write_json {out}"
    result = subprocess.run(["yosys", "-q", "-p", script], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    ports = json.loads(out.read_text())["modules"][top]["ports"]
    return {name: (port["direction"], len(port["bits"])) for name, port in ports.items()}


def test_the_verilog_rendering_elaborates_in_yosys_with_the_vhdl_ports(tmp_path):
    start_new_design()
    files = convert_myhdl(counter_instance(), "counter8", tmp_path)
    top = tmp_path / "pair.v"
    top.write_text(two_counters().render_verilog())
    assert top.read_text().startswith("// two counters side by side\n")
    assert yosys_ports([files[-1], top], "pair", tmp_path) == {
        "clk": ("input", 1),
        "resetn": ("input", 1),
        "counts": ("output", 16),
    }


def test_verilog_keywords_are_escaped_so_every_tool_sees_the_same_name(tmp_path):
    start_new_design()
    files = convert_myhdl(counter_instance(), "counter8", tmp_path)
    top = Netlist(
        EntityDecl(
            "keywords",
            (PortDecl("clk", Direction.IN, 1, wire=True), PortDecl("reg", Direction.OUT, 8)),
        )
    )
    wire = top.signal("wire", wire=True)
    top.assign(wire, "not clk")
    top.instance(
        "module",
        COUNTER,
        {"clk": top.port("clk"), "rst": wire, "enable": wire, "count": top.port("reg")},
    )
    (tmp_path / "keywords.v").write_text(top.render_verilog())
    ports = yosys_ports([files[-1], tmp_path / "keywords.v"], "keywords", tmp_path)
    assert ports == {"clk": ("input", 1), "reg": ("output", 8)}


def test_only_the_inversion_of_a_wire_is_accepted_as_expression_text():
    top = two_counters()
    with pytest.raises(NetlistError, match="'resetn and clk' is not the inversion"):
        top.assign(top.signal("other", wire=True), "resetn and clk")
