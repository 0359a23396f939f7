"""The module cache of `--estimate`: shared by parallel builds without mapping a module twice."""

from __future__ import annotations

import re
from concurrent.futures import ThreadPoolExecutor

import pytest

from rfc.toolchain import convert_myhdl, crossing_timing, module_estimates, yosys
from tests.toolchain.counter import counter_instance

COUNTER = """
module counter (input clk, output reg [7:0] count);
  always @(posedge clk) count <= count + 8'd1;
endmodule
"""
#: A counter under a name of its own; two of them, the second stepped by the first's top bit.
NAMED_COUNTER = """
// {name}: a counter
module {name} (input clk, input step, output reg [7:0] count);
  always @(posedge clk) if (step) count <= count + 8'd1;
endmodule
"""
TWO_COUNTERS = """
module two (input clk, output [7:0] total);
  wire [7:0] low;
  first_counter a (.clk(clk), .step(1'b1), .count(low));
  second_counter b (.clk(clk), .step(low[7]), .count(total));
endmodule
"""


def recorded_scripts(monkeypatch) -> list[str]:
    """The Yosys scripts the module cache runs from now on, in order (each still run)."""
    scripts: list[str] = []
    run_yosys = yosys._run_yosys

    def recorded(script, what):
        scripts.append(script)
        run_yosys(script, what)

    monkeypatch.setattr(yosys, "_run_yosys", recorded)
    return scripts


def test_two_builds_needing_one_module_at_once_map_it_once(tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    source = tmp_path / "counter.v"
    source.write_text(COUNTER)
    scripts = recorded_scripts(monkeypatch)
    with ThreadPoolExecutor(max_workers=2) as pool:
        first, second = pool.map(
            lambda _: module_estimates.module_estimate(source, "counter"), range(2)
        )
    assert len(scripts) == 1
    assert first == second
    assert first.resources.ff == 8
    assert first.timing is not None


def test_the_largest_module_is_mapped_first_and_figures_come_back_in_the_order_asked(
    tmp_path, monkeypatch
):
    files = []
    for name, lines in (("small", 1), ("large", 40), ("medium", 8)):
        path = tmp_path / f"{name}.v"
        path.write_text("// padding\n" * lines + f"module {name} (); endmodule\n")
        files.append((path, name))
    started = []

    def recorded(verilog, top, submodules=()):
        started.append((top, tuple(submodules)))
        return top

    monkeypatch.setattr(module_estimates, "module_estimate", recorded)
    monkeypatch.setattr(module_estimates, "WORKERS", 1)
    inside = {"large": [files[0][0]]}  # the large module instantiates the small one
    assert module_estimates.estimate_modules(files, inside) == ["small", "large", "medium"]
    assert started == [("large", (files[0][0],)), ("medium", ()), ("small", ())]


def test_a_block_under_another_name_is_mapped_once_and_named_as_each_instance_wants(
    tmp_path, monkeypatch
):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    files = {}
    for name in ("first_counter", "second_counter"):
        files[name] = tmp_path / f"{name}.v"
        files[name].write_text(NAMED_COUNTER.format(name=name))
    scripts = []
    run_yosys = yosys._run_yosys

    def counted(script, what):
        scripts.append(script)
        run_yosys(script, what)

    monkeypatch.setattr(yosys, "_run_yosys", counted)
    first, second = (module_estimates.module_estimate(files[n], n) for n in files)
    assert len(scripts) == 1
    assert (first.resources, first.timing) == (second.resources, second.timing)
    assert "module first_counter" in first.netlist.read_text()
    assert "module second_counter" in second.netlist.read_text()
    # the top level finds each under its own name: the path from a's count into b's enable
    top = tmp_path / "two.v"
    top.write_text(TWO_COUNTERS)
    across = crossing_timing([first.netlist, second.netlist], top, "two")
    assert across is not None
    assert (across.start_cell, across.end_cell) == ("a", "b")


def test_a_vhdl_design_is_counted_and_timed_as_its_verilog_is(tmp_path, monkeypatch):
    # GHDL's synthesis of the VHDL and MyHDL's Verilog of one counter map to the same cells
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    *vhdl, verilog = convert_myhdl(counter_instance(), "counter8", tmp_path / "hdl")
    mapped = module_estimates.module_estimate(verilog, "counter8")
    assert yosys.estimate_resources(vhdl, "counter8") == mapped.resources
    timed = yosys.estimate_timing(vhdl, "counter8")
    assert timed is not None
    assert mapped.timing is not None
    assert (timed.delay_ps, timed.levels) == (mapped.timing.delay_ps, mapped.timing.levels)


RAM = """
module ram (input clk, input we, input [10:0] addr, input [31:0] din, output reg [31:0] dout);
  reg [31:0] memory [0:2047];
  always @(posedge clk) begin
    if (we) memory[addr] <= din;
    dout <= memory[addr];
  end
endmodule
"""


def _estimated(tmp_path, monkeypatch, top: str, verilog: str) -> module_estimates.ModuleEstimate:
    """`module_estimate` of module `top` of `verilog`, in a module cache of the test's own."""
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    source = tmp_path / f"{top}.v"
    source.write_text(verilog)
    return module_estimates.module_estimate(source, top)


def test_a_module_with_a_block_ram_is_counted_in_block_ram_and_timed(tmp_path, monkeypatch):
    # Yosys 0.23's abc9 aborts on a block RAM: counted without it, timed in distributed RAM
    scripts = recorded_scripts(monkeypatch)
    mapped = _estimated(tmp_path, monkeypatch, "ram", RAM)
    # the first mapping stops where it finds the block RAM; abc9 never meets one
    assert len(scripts) == 3
    assert not any("-abc9" in s and "brams_xc6v_map" in s for s in scripts)
    assert mapped.resources.bram >= 1
    assert mapped.resources.lutram == 0
    assert mapped.timing is not None
    assert "module ram" in mapped.netlist.read_text()


LOGGER = """
module logger (input clk, input we, input [3:0] addr, input [7:0] din, output [7:0] dout,
               output reg [7:0] count);
  reg [7:0] memory [0:15];
  always @(posedge clk) begin
    if (we) memory[addr] <= din;
    count <= count + 1;
  end
  assign dout = memory[addr];
endmodule
"""


@pytest.mark.parametrize(("top", "verilog"), [("counter", COUNTER), ("logger", LOGGER)])
def test_mapping_with_fewer_libraries_gives_synth_xilinxs_own_netlist(tmp_path, top, verilog):
    # synth_xilinx whole reads cells_xtra.v and the block-RAM mapping too; rfc leaves them out
    # where nothing needs them (the logger's memory goes to distributed RAM)
    source = tmp_path / f"{top}.v"
    source.write_text(verilog)
    outputs = {}
    for flow in ("whole", "rfc"):
        work = tmp_path / flow
        work.mkdir()
        script = yosys.estimate_script(source, top, work)
        assert "cells_xtra" not in script
        assert "brams_xc6v_map" not in script
        if flow == "whole":
            script = (
                f"read_verilog {source}; synth_xilinx -family xc7 -noiopad -abc9 -flatten "
                f"-top {top}; tee -q -o {work / 'stat.json'} stat -json; "
                f"{yosys._timing_and_boundary(yosys.Module(source, top), work)}"
            )
        yosys._run_yosys(script, flow)
        outputs[flow] = [_numbered_alike((work / f).read_text()) for f in yosys_outputs]
    assert outputs["rfc"] == outputs["whole"]
    if top == "logger":
        assert '"RAM32M"' in outputs["rfc"][0] or '"RAM16X1D"' in outputs["rfc"][0]


#: What `estimate_script` writes: cell counts, the timing report, the boundary netlist.
yosys_outputs = ("stat.json", "sta.log", "boundary.v")


def _numbered_alike(text: str) -> str:
    """Yosys' output with its running numbers left out (names ``$abc$2476$…``, step numbers).

    Reading fewer libraries changes only how far Yosys' counters of fresh names have run.
    """
    return re.sub(r"(?<=\$)\d+|(?<=\$aiger)\d+|^\d+\. ", "", text, flags=re.M)


TEMPERATURE = """
module temperature (input clk, output reg [15:0] sample);
  wire [15:0] measured;
  XADC adc (.DCLK(clk), .DO(measured));
  always @(posedge clk) sample <= measured;
endmodule
"""


def test_a_module_instantiating_another_7_series_primitive_is_mapped(tmp_path, monkeypatch):
    # XADC is one of the primitives rfc reads only when a design instantiates one
    mapped = _estimated(tmp_path, monkeypatch, "temperature", TEMPERATURE)
    assert mapped.resources.ff == 16
    assert mapped.timing is not None
