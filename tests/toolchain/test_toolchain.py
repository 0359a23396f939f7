"""The HDL toolchain wrappers on a small design: conversion, GHDL, Yosys, cocotb."""

from __future__ import annotations

import pytest

from rfc.toolchain import (
    CosimError,
    GhdlError,
    analyze,
    convert_myhdl,
    estimate_resources,
    read_entities,
    run_cocotb,
    synthesize_vhdl,
)
from tests.toolchain.counter import counter_instance


@pytest.fixture
def counter_files(tmp_path):
    return convert_myhdl(counter_instance(), "counter8", tmp_path / "hdl", header="rfc test")


def test_conversion_is_reproducible(tmp_path, counter_files):
    again = convert_myhdl(counter_instance(), "counter8", tmp_path / "again", header="rfc test")
    assert [f.name for f in counter_files] == ["pck_myhdl_011.vhd", "counter8.vhd", "counter8.v"]
    for first, second in zip(counter_files, again, strict=True):
        assert first.read_text() == second.read_text()
    assert counter_files[1].read_text().startswith("-- rfc test\n")
    assert "Date" not in counter_files[1].read_text()


def test_ghdl_analyzes_and_elaborates(tmp_path, counter_files):
    analyze(counter_files, tmp_path / "work", top="counter8")


def test_ghdl_reports_bad_vhdl(tmp_path):
    bad = tmp_path / "bad.vhd"
    bad.write_text("entity bad is port (a : in bit) end;\n")
    with pytest.raises(GhdlError, match="failed"):
        analyze([bad], tmp_path / "work")


def test_yosys_counts_an_eight_bit_counter(counter_files):
    resources = estimate_resources(counter_files, "counter8")
    assert resources.ff == 8
    assert 0 < resources.lut + resources.carry <= 16


def test_cocotb_passes_and_fails(tmp_path, counter_files):
    ran = run_cocotb(counter_files, "counter8", "tests.toolchain.counter", tmp_path / "ok")
    assert ran == 1
    with pytest.raises(CosimError, match="count 7 != 8"):
        run_cocotb(
            counter_files,
            "counter8",
            "tests.toolchain.counter",
            tmp_path / "fail",
            env={"COUNTER_CYCLES": "7", "COUNTER_EXPECT": "8"},
        )


def test_read_entities_with_ghdls_parser(tmp_path):
    source = tmp_path / "acc.vhd"
    source.write_text(
        "library ieee; use ieee.std_logic_1164.all;\n"
        "entity Acc is\n"
        "  generic (N : integer := 4);\n"
        "  port (\n"
        "    clk, rst : in std_logic;\n"
        "    q_x : in std_logic_vector(63 downto 0);\n"
        "    euler_x : out std_logic_vector(0 to 63);\n"
        "    wide : out std_logic_vector(N - 1 downto 0)\n"
        "  );\n"
        "end entity;\n"
        "architecture a of acc is begin end;\n"
    )
    (entity,) = read_entities(source)
    assert (entity.name, entity.line) == ("acc", 2)
    assert [(p.name, p.mode, p.bits, p.wire, p.line) for p in entity.ports] == [
        ("clk", "in", 1, True, 5),
        ("rst", "in", 1, True, 5),
        ("q_x", "in", 64, False, 6),
        ("euler_x", "out", 64, False, 7),
        ("wide", "out", None, False, 8),
    ]


def test_read_entities_reports_syntax_errors(tmp_path):
    source = tmp_path / "bad.vhd"
    source.write_text("entity bad is port (a : in bit) end;\n")
    with pytest.raises(GhdlError, match=r"bad\.vhd"):
        read_entities(source)


ONE_BIT = """library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity one_bit is
  port (clk : in std_logic; bit_in : in std_logic;
        vector_out : out std_logic_vector(0 downto 0); below_one : out std_logic);
end entity;

architecture rtl of one_bit is
  signal beat : unsigned(0 downto 0) := "0";
begin
  process (clk) begin
    if rising_edge(clk) then beat <= beat + 1; end if;
  end process;
  vector_out(0) <= bit_in;
  below_one <= '1' when beat < 1 else '0';
end architecture;
"""


def test_a_netlist_of_one_bit_vectors_is_analysable_by_ghdl(tmp_path):
    # GHDL 2.0 writes std_ulogic_vector(bit) and unsigned'('1') for these, which it refuses
    source = tmp_path / "one_bit.vhd"
    source.write_text(ONE_BIT)
    netlist = tmp_path / "one_bit_netlist.vhd"
    netlist.write_text(synthesize_vhdl([source], "one_bit", tmp_path / "synth"))
    analyze([netlist], tmp_path / "work", "one_bit")
