"""The structural VHDL builder: checked wiring, and output GHDL accepts."""

from __future__ import annotations

import pytest

from rfc.lower.netlist import EntityDecl, Mode, Netlist, NetlistError, PortDecl, constant
from rfc.toolchain import analyze, convert_myhdl, start_new_design
from tests.toolchain.counter import counter_instance

COUNTER = EntityDecl(
    "counter8",
    (
        PortDecl("clk", Mode.IN, 1, wire=True),
        PortDecl("rst", Mode.IN, 1, wire=True),
        PortDecl("enable", Mode.IN, 1, wire=True),
        PortDecl("count", Mode.OUT, 8),
    ),
)


def two_counters():
    top = Netlist(
        EntityDecl(
            "pair",
            (
                PortDecl("clk", Mode.IN, 1, wire=True),
                PortDecl("resetn", Mode.IN, 1, wire=True),
                PortDecl("counts", Mode.OUT, 16),
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
    lonely = Netlist(EntityDecl("lonely", (PortDecl("o", Mode.OUT, 2),)))
    with pytest.raises(NetlistError, match=r"o\(0\) has no driver"):
        lonely.render()


def test_inputs_cannot_be_left_open():
    top = two_counters()
    with pytest.raises(NetlistError, match="input clk must be driven"):
        top.instance("c", COUNTER, {"clk": None, "rst": None, "enable": None, "count": None})
