"""Which rfc.lib blocks a MyHDL design instantiates, by name, variant and parameters."""

from __future__ import annotations

from myhdl import ResetSignal, Signal, always_seq, block, intbv

from rfc.lib.arith import SinCosConfig
from rfc.lib.arith.convert_hdl import float_to_fixed_pipelined
from rfc.lib.arith.sincos_hdl import sincos
from rfc.lib.arith.timing import BlockKey, blocks_in
from rfc.lib.fixed import FixedFormat
from rfc.toolchain import elaboration

FORMAT = FixedFormat(50, 44)
CONFIG = SinCosConfig(44)


@block
def float_sine(clk, rst, in_valid, in_ready, bits, out_valid, out_ready, cos, sin):
    """A user's block: a pipelined float → fixed converter into an iterative sine/cosine."""
    raw, angle = FORMAT.signal(), CONFIG.angle_format.signal()
    converted, taken = Signal(bool(0)), Signal(bool(0))
    overflow, invalid = Signal(bool(0)), Signal(bool(0))
    convert = float_to_fixed_pipelined(
        clk, rst, in_valid, in_ready, bits, converted, taken, raw, overflow, invalid, FORMAT
    )
    unit = sincos(clk, rst, converted, taken, angle, out_valid, out_ready, cos, sin, CONFIG)

    @always_seq(clk.posedge, reset=rst)
    def scale():
        angle.next = raw

    return convert, unit, scale


def elaborated():
    signals = [Signal(bool(0)), ResetSignal(0, active=1, isasync=False)]
    signals += [Signal(bool(0)), Signal(bool(0)), Signal(intbv(0)[64:])]
    signals += [Signal(bool(0)), Signal(bool(0))]
    signals += [CONFIG.out_format.signal(), CONFIG.out_format.signal()]
    with elaboration():
        return float_sine(*signals)


def test_the_blocks_of_a_design_are_named_with_their_parameters():
    assert blocks_in(elaborated()) == (
        BlockKey("float_to_fixed", "pipelined", "Q6.44"),
        BlockKey("sincos", "iterative", "Q4.44, 46 iterations, 8 guard bits"),
    )
