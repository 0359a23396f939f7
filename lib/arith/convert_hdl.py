"""Pipelined (II = 1) float64 ↔ fixed converters: `rfc.lib.fixed`'s blocks between registers.

The combinational converters sit between an input and an output register, so each takes a
value every cycle with valid/ready handshakes and a latency of `CONVERT_LATENCY` cycles, and
holds its result until taken; the bits are those of `rfc.lib.fixed.ieee754`.
"""

from __future__ import annotations

from myhdl import Signal, always_seq, block, intbv

from rfc.lib.arith.pipeline import stall_control
from rfc.lib.fixed.hdl import fixed_to_float, float_to_fixed

#: Input and output registers.
CONVERT_LATENCY = 1


@block
def float_to_fixed_pipelined(
    clk, rst, in_valid, in_ready, bits, out_valid, out_ready, raw, overflow, invalid, fmt
):
    """Float64 bit pattern → raw `fmt`, ties to even, saturating (`ieee754.float_to_fixed`).

    Args:
        clk: Clock.
        rst: Synchronous reset (a MyHDL ``ResetSignal``).
        in_valid: Input, `bits` holds a value to take.
        in_ready: Output, the block takes the value on this cycle when `in_valid` is high.
        bits: Input, 64-bit IEEE-754 pattern.
        out_valid: Output, `raw`, `overflow` and `invalid` hold a result.
        out_ready: Input, the consumer takes the result on this cycle.
        raw: Output, raw integer of `fmt`.
        overflow: Output, the value lay outside `fmt` (or was ±Inf) and was saturated.
        invalid: Output, the value was a NaN (`raw` is 0).
        fmt: The fixed-point format.
    """
    held = Signal(intbv(0)[64:])
    converted, converted_overflow, converted_invalid = (
        fmt.signal(),
        Signal(bool(0)),
        Signal(bool(0)),
    )
    v1, v2, advance = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    convert = float_to_fixed(held, converted, converted_overflow, converted_invalid, fmt)

    @always_seq(clk.posedge, reset=rst)
    def stages():
        if advance:
            held.next = bits
            v1.next = in_valid
            raw.next = converted
            overflow.next = converted_overflow
            invalid.next = converted_invalid
            v2.next = v1

    control = stall_control(v2, out_ready, advance, in_ready, out_valid)

    return convert, stages, control


@block
def fixed_to_float_pipelined(clk, rst, in_valid, in_ready, raw, out_valid, out_ready, bits, fmt):
    """Raw `fmt` → float64 bit pattern, ties to even (`ieee754.fixed_to_float`).

    Args:
        clk: Clock.
        rst: Synchronous reset (a MyHDL ``ResetSignal``).
        in_valid: Input, `raw` holds a value to take.
        in_ready: Output, the block takes the value on this cycle when `in_valid` is high.
        raw: Input, raw integer of `fmt`.
        out_valid: Output, `bits` holds a result.
        out_ready: Input, the consumer takes the result on this cycle.
        bits: Output, 64-bit IEEE-754 pattern.
        fmt: The fixed-point format.
    """
    held = fmt.signal()
    converted = Signal(intbv(0)[64:])
    v1, v2, advance = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    convert = fixed_to_float(held, converted, fmt)

    @always_seq(clk.posedge, reset=rst)
    def stages():
        if advance:
            held.next = raw
            v1.next = in_valid
            bits.next = converted
            v2.next = v1

    control = stall_control(v2, out_ready, advance, in_ready, out_valid)

    return convert, stages, control
