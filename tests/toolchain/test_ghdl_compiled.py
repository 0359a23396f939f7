"""GHDL's compiled logic: one program per content of the VHDL, nothing left when it fails."""

from __future__ import annotations

import subprocess

import pytest

from rfc.toolchain.cocotb_sim import CosimError, compile_logic, compiled_logic
from rfc.toolchain.ghdl import fastest_backend

COUNTER = """\
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity counter is
  port (clk, rst : in std_logic; count : out unsigned(3 downto 0));
end entity counter;

architecture rtl of counter is
  signal value : unsigned(3 downto 0) := (others => '0');
begin
  step: process ({sensitivity}) is
  begin
    if rising_edge(clk) then
      if rst = '1' then
        value <= (others => '0');
      else
        value <= value + 1;
      end if;
    end if;
  end process step;
  count <= value;
end architecture rtl;
"""


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("GHDL_BACKEND", raising=False)
    fastest_backend.cache_clear()
    yield tmp_path / "cache" / "ghdl"
    fastest_backend.cache_clear()


def test_the_program_is_compiled_once_and_keyed_by_content(tmp_path, cache):
    source = tmp_path / "counter.vhd"
    source.write_text(COUNTER.format(sensitivity="clk, rst"))
    logic = compiled_logic([source], "counter", fastest_backend())
    assert not logic.compiled
    compile_logic(logic, [source])
    assert logic.compiled
    assert [entry.name for entry in cache.iterdir()] == [logic.folder.name]
    # runs as GHDL's own program: its options are the simulation's
    run = subprocess.run([str(logic.program), "--stop-time=100ns"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    # MyHDL writes a sensitivity list in any order: the same logic
    source.write_text(COUNTER.format(sensitivity="rst, clk"))
    assert compiled_logic([source], "counter", fastest_backend()) == logic
    source.write_text(COUNTER.format(sensitivity="clk, rst").replace("value + 1", "value + 2"))
    changed = compiled_logic([source], "counter", fastest_backend())
    assert changed.folder != logic.folder
    assert not changed.compiled


def test_vhdl_ghdl_refuses_leaves_nothing_in_the_cache(tmp_path, cache):
    source = tmp_path / "counter.vhd"
    source.write_text(COUNTER.format(sensitivity="clk, rst").replace("value + 1", "value + "))
    logic = compiled_logic([source], "counter", fastest_backend())
    with pytest.raises(CosimError, match="GHDL could not compile counter"):
        compile_logic(logic, [source])
    assert list(cache.iterdir()) == []
