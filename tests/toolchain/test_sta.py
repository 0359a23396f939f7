"""Timing estimates: Yosys `sta` on the 7-series mapping, per module and across modules."""

from __future__ import annotations

import pytest

from rfc.toolchain import module_estimate, system_timing
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
PAIR = """
module pair (input clk, output [15:0] result);
  wire [15:0] handed;
  producer make (.clk(clk), .out(handed));
  consumer take (.clk(clk), .in(handed), .result(result));
endmodule
"""


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))


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


def test_module_figures_come_back_from_the_cache_with_their_netlist(tmp_path):
    source = write_adder(tmp_path, 8)
    first = module_estimate(source, "adder8")
    again = module_estimate(source, "adder8")
    assert again == first
    assert first.resources.ff == 24
    assert "CARRY4" in first.netlist.read_text()


def test_the_whole_design_finds_the_path_that_crosses_two_blocks(tmp_path):
    files = {name: tmp_path / f"{name}.v" for name in ("producer", "consumer", "pair")}
    for name, text in (("producer", PRODUCER), ("consumer", CONSUMER), ("pair", PAIR)):
        files[name].write_text(text)
    parts = [module_estimate(files[n], n) for n in ("producer", "consumer")]
    whole = system_timing([p.netlist for p in parts], files["pair"], "pair")
    assert whole is not None
    assert (whole.start_cell, whole.end_cell) == ("make", "take")
    assert whole.start.startswith("make.count")
    assert whole.end.startswith("take.result")
    # each block alone ends or starts at its port; together the two halves add up
    assert whole.delay_ps > max(p.timing.delay_ps for p in parts if p.timing)


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
