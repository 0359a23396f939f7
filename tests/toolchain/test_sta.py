"""Timing estimates: Yosys `sta` on the 7-series mapping, per module and across modules."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from rfc.toolchain import crossing_timing, logic_timing, module_estimate
from rfc.toolchain.sta import ROUTING_FACTOR, parse_sta

#: A register feeding an adder of `bits` bits into a register, and a wire from input to output.
ADDER = """
module adder{bits} (input clk, input [{top}:0] a, input [{top}:0] b, input i, output o,
                    output reg [{top}:0] sum);
  reg [{top}:0] ra, rb;
  assign o = ~i;
  always @(posedge clk) begin
    ra <= a;
    rb <= b;
    sum <= ra + rb;
  end
endmodule
"""

#: Two blocks: `producer` registers a count and hands on a function of it without a register,
#: `consumer` takes that into more logic before its register. Each alone has short paths.
PRODUCER = """
module producer (input clk, output [15:0] out);
  reg [15:0] count;
  assign out = count + {count[7:0], count[15:8]};
  always @(posedge clk) count <= count + 16'd1;
endmodule
"""
CONSUMER = """
module consumer (input clk, input [15:0] in, output reg [15:0] result);
  always @(posedge clk) result <= in + {in[3:0], in[15:4]};
endmodule
"""
#: The producer with its output registered: the longest path is then inside it (48-bit adder).
REGISTERED_PRODUCER = """
module producer (input clk, output reg [15:0] out);
  reg [47:0] count, step;
  always @(posedge clk) begin
    count <= count + step;
    step <= step ^ {count[46:0], count[47]};
    out <= count[15:0];
  end
endmodule
"""
PAIR = """
module pair (input clk, output [15:0] result);
  wire [15:0] handed;
  producer make (.clk(clk), .out(handed));
  consumer take (.clk(clk), .in(handed), .result(result));
endmodule
"""


#: The pair's instances and the module each is.
PAIR_INSTANCES = {"make": "producer", "take": "consumer"}


@pytest.fixture(scope="module")
def module_cache(tmp_path_factory):
    """One cache for the module's tests: a block two tests map is mapped once, as in a build."""
    return tmp_path_factory.mktemp("cache")


@pytest.fixture(autouse=True)
def shared_cache(module_cache, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(module_cache))


def write_adder(folder, bits):
    path = folder / f"adder{bits}.v"
    path.write_text(ADDER.format(bits=bits, top=bits - 1))
    return path


def test_a_wider_adder_has_a_longer_carry_path_between_its_registers(tmp_path):
    narrow = module_estimate(write_adder(tmp_path, 4), "adder4").timing
    wide = module_estimate(write_adder(tmp_path, 64), "adder64").timing
    assert narrow is not None
    assert wide is not None
    # from an operand register through the carry chain into the sum register
    assert narrow.start.startswith(("ra", "rb"))
    assert narrow.end.startswith("sum")
    assert wide.start.startswith(("ra", "rb"))
    assert wide.end.startswith("sum")
    # 64 bits take 16 CARRY4 in a row where 4 bits take one
    assert wide.delay_ps > narrow.delay_ps + 15 * 100
    assert wide.fmax_mhz < narrow.fmax_mhz
    assert wide.fmax_mhz == pytest.approx(1e6 / (ROUTING_FACTOR * wide.delay_ps))


def test_module_figures_come_back_from_the_cache_with_their_boundary_logic(tmp_path):
    source = write_adder(tmp_path, 8)
    first = module_estimate(source, "adder8")
    again = module_estimate(source, "adder8")
    assert again == first
    assert first.resources.ff == 24
    assert first.resources.carry > 0
    boundary = first.netlist.read_text()
    # the registers at the ports and the inverter from i to o, not the adder between registers
    assert "ra[0]" in boundary
    assert "sum[7]" in boundary
    assert "INV" in boundary
    assert "CARRY4" not in boundary


def write_pair(folder, producer=PRODUCER):
    """The two blocks and their top level; returns each block's estimate and the top's file."""
    files = {name: folder / f"{name}.v" for name in ("producer", "consumer", "pair")}
    for name, text in (("producer", producer), ("consumer", CONSUMER), ("pair", PAIR)):
        files[name].write_text(text)
    parts = {label: module_estimate(files[m], m) for label, m in PAIR_INSTANCES.items()}
    return parts, files


@pytest.fixture(scope="module")
def whole_netlist(tmp_path_factory):
    """`whole_netlist(source, top)`: `top` mapped as `module_estimate` maps it, every cell kept.

    The flattened oracle's input; a block the tests share (the consumer) is mapped once.
    """
    folder = tmp_path_factory.mktemp("whole")
    mapped: dict[str, Path] = {}

    def netlist(source: Path, top: str) -> Path:
        text = source.read_text()
        if text not in mapped:
            mapped[text] = map_whole(source, top, folder / f"{top}{len(mapped)}.whole.v")
        return mapped[text]

    return netlist


def map_whole(source, top, mapped, submodules=()):
    """Map `source` with `module_estimate`'s mapping into `mapped`, every cell kept."""
    libraries = "".join(f"read_verilog -lib {f}; " for f in submodules)
    script = (
        f"{libraries}read_verilog {source}; "
        f"synth_xilinx -family xc7 -noiopad -abc9 -flatten -top {top}; "
        f"rename -wire t:FD*; write_verilog -noattr {mapped}"  # registers named as rfc names them
    )
    subprocess.run([shutil.which("yosys") or "yosys", "-q", "-p", script], check=True)
    return mapped


def test_the_whole_design_finds_the_path_that_crosses_two_blocks(tmp_path):
    parts, files = write_pair(tmp_path)
    whole = logic_timing(parts, files["pair"], "pair")
    assert whole is not None
    assert (whole.start_cell, whole.end_cell) == ("make", "take")
    assert whole.start.startswith("make.count")
    assert whole.end.startswith("take.result")
    # each block alone ends or starts at its port; together the two halves add up
    assert whole.delay_ps > max(p.timing.delay_ps for p in parts.values() if p.timing)


@pytest.mark.parametrize("producer", [PRODUCER, REGISTERED_PRODUCER], ids=["across", "inside"])
def test_the_boundary_logic_times_a_logic_as_its_whole_flattened_netlist_does(
    tmp_path, producer, whole_netlist
):
    parts, files = write_pair(tmp_path, producer)
    netlists = [whole_netlist(files[m], m) for m in ("producer", "consumer")]
    flattened = crossing_timing(netlists, files["pair"], "pair")
    assert flattened is not None
    assert logic_timing(parts, files["pair"], "pair") == flattened
    boundaries = sum(len(p.netlist.read_text()) for p in parts.values())
    assert boundaries < sum(len(n.read_text()) for n in netlists)


#: The pair inside a block of its own, with the block's logic between them: the producer's
#: unregistered output goes through the block's adder into the consumer's. The block is mapped
#: with its two instances as black boxes, each instance on its own (`rfc.toolchain.modules`).
NEST = """
module nest (input clk, output [15:0] result);
  wire [15:0] handed, mixed;
  reg [15:0] bias;
  always @(posedge clk) bias <= bias + 16'd3;
  assign mixed = handed + bias;
  producer make (.clk(clk), .out(handed));
  consumer take (.clk(clk), .in(mixed), .result(result));
endmodule
"""
SYSTEM = """
module system (input clk, output [15:0] result);
  nest inner (.clk(clk), .result(result));
endmodule
"""


def test_a_path_through_a_block_and_its_submodules_is_timed_as_the_flattened_whole(
    tmp_path, whole_netlist
):
    texts = {"producer": PRODUCER, "consumer": CONSUMER, "nest": NEST, "system": SYSTEM}
    files = {name: tmp_path / f"{name}.v" for name in texts}
    for name, text in texts.items():
        files[name].write_text(text)
    inside = [files["producer"], files["consumer"]]
    nest = module_estimate(files["nest"], "nest", inside)
    parts = {
        "inner": nest,
        "inner.make": module_estimate(files["producer"], "producer"),
        "inner.take": module_estimate(files["consumer"], "consumer"),
    }
    assert nest.resources.ff == 16  # its own register; the submodules' cells are theirs
    path = logic_timing(parts, files["system"], "system")
    assert path is not None
    assert path.start.startswith("inner.make.count")
    assert path.end.startswith("inner.take.result")
    # the oracle: every module's whole netlist, flattened together
    netlists = [whole_netlist(files[m], m) for m in ("producer", "consumer")]
    netlists.append(map_whole(files["nest"], "nest", tmp_path / "nest.whole.v", inside))
    assert path == crossing_timing(netlists, files["system"], "system")
    assert path.delay_ps > max(p.timing.delay_ps for p in parts.values() if p.timing)


LOG = """
Latest arrival time in 'sub' is 2961:
    2961 count_FDRE_Q_4 (FDRE.D)
           \\count_FDRE_Q_D [4]
    2961 count_FDRE_Q_D_LUT3_O_3 (LUT3.I2->O)
           \\count_FDRE_Q_D_LUT3_O_3_I2 [2]
    2834 count_CARRY4_O (CARRY4.CI->O)
           \\count [3]
     399 count_FDRE_Q_3 (FDRE.C->Q)
           \\clk_BUFG_I_O
      96 clk_BUFG_I (BUFG.I->O)
       0   \\clk (<primary input>)

Arrival histogram:
"""


def test_the_report_is_read_from_the_launching_clock_to_the_capturing_register():
    path = parse_sta(LOG)
    assert path is not None
    assert (path.start, path.end, path.levels) == ("count", "count", 2)
    assert path.delay_ps == 2961 - 96  # the clock buffer delays launch and capture alike


def test_a_path_from_an_input_to_an_output_names_both_ports():
    log = (
        "Latest arrival time in 'm' is 124:\n"
        "     124 (<primary output>)\n"
        "           \\o\n"
        "     124 o_LUT1_O (LUT1.I0->O)\n"
        "           \\i\n"
        "       0   \\i (<primary input>)\n"
    )
    path = parse_sta(log)
    assert path is not None
    assert (path.start, path.end, path.levels, path.delay_ps) == ("i", "o", 1, 124)


def test_no_report_is_an_error_and_no_path_is_none():
    assert parse_sta("No timing paths found.\n") is None
    with pytest.raises(ValueError, match="no static timing report"):
        parse_sta("")


def test_a_path_into_a_carry_output_nothing_reads_is_named_after_its_logic():
    log = (
        "Latest arrival time in 'sub' is 2990:\n"
        "    2990 (<unknown>)\n"
        "Warning: Critical-path does not terminate in a recognised endpoint.\n"
        "           \\count_FDRE_Q_D_CARRY4_O_O [3]\n"
        "    2990 count_FDRE_Q_D_CARRY4_O (CARRY4.DI->O)\n"
        "           \\count [1]\n"
        "     399 count_FDRE_Q_1 (FDRE.C->Q)\n"
        "           \\clk_BUFG_I_O\n"
        "      96 clk_BUFG_I (BUFG.I->O)\n"
        "       0   \\clk (<primary input>)\n"
    )
    path = parse_sta(log)
    assert path is not None
    assert (path.start, path.end, path.levels, path.delay_ps) == ("count", "count", 1, 2894)


def test_logic_without_a_name_is_named_after_the_register_it_comes_from():
    log = (
        "Latest arrival time in 'sub' is 2990:\n"
        "    2990 (<unknown>)\n"
        "Warning: Critical-path does not terminate in a recognised endpoint.\n"
        "           $abc$58928$aiger58927$595\n"
        "    2990 $auto$alumacc.cc:485:replace_alu$18438.carry4 (CARRY4.DI->O)\n"
        "           $abc$58928$aiger58927$665\n"
        "    1030 $abc$58928$lut$aiger58927$665 (LUT5.I0->O)\n"
        "           \\window_count [3]\n"
        "     399 window_count[3]\\FDRE (FDRE.C->Q)\n"
        "           $auto$clkbufmap.cc:294:execute$60237\n"
        "      96 $auto$clkbufmap.cc:261:execute$60236 (BUFG.I->O)\n"
        "           \\clk\n"
        "       0   \\clk (<primary input>)\n"
    )
    path = parse_sta(log)
    assert path is not None
    assert (path.start, path.end, path.levels, path.delay_ps) == (
        "window_count",
        "window_count",
        2,
        2990 - 96,
    )


def test_a_cell_without_a_name_is_named_after_the_signal_it_comes_from_and_its_type():
    log = (
        "Latest arrival time in 'top' is 8786:\n"
        "    8786 core.$mul$/tmp/rfc-hw-1/core.v:2011$220 (DSP48E1.B)\n"
        "           core.$abc$1$aiger1$7 [3]\n"
        "    8000 core.$abc$1$lut$aiger1$7 (LUT6.I0->O)\n"
        "           \\core.stage_target [5]\n"
        "     399 core.stage_target[5]\\FDRE (FDRE.C->Q)\n"
        "           \\clk_buffered\n"
        "      96 core.$auto$clkbufmap$1 (BUFG.I->O)\n"
        "           \\clk\n"
        "       0   \\clk (<primary input>)\n"
    )
    path = parse_sta(log)
    assert path is not None
    assert (path.start, path.end, path.levels) == (
        "core.stage_target",
        "core.stage_target (DSP48E1)",
        1,
    )
