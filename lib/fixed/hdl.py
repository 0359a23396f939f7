"""MyHDL blocks converting float64 bit patterns to signed fixed point and back.

Both blocks are combinational (register around them as timing needs) and bit-exact with the
models in `rfc.lib.fixed.ieee754`. Every constant wider than 31 bits is built from bit
operations, because VHDL integers stop at 32 bits.
"""

from __future__ import annotations

from myhdl import always_comb, block, concat, intbv

from rfc.lib.fixed.format import FixedFormat
from rfc.lib.fixed.ieee754 import EXPONENT_ALL_ONES, MANTISSA_BITS, ROUNDING_BITS
from rfc.lib.fixed.layout import SIGNIFICAND_BITS, to_fixed_layout, to_float_layout
from rfc.lib.types import Instances, SignalLike


@block
def float_to_fixed(
    bits: SignalLike, raw: SignalLike, overflow: SignalLike, invalid: SignalLike, fmt: FixedFormat
) -> Instances:
    """Float64 → fixed point, rounding to nearest with ties to even (combinational).

    Args:
        bits: Input, 64-bit IEEE-754 pattern (unsigned ``intbv[64:]``).
        raw: Output, the raw integer of `fmt` (signed ``intbv`` of ``fmt.width`` bits).
        overflow: Output, the input lay outside `fmt` or was ±Inf: `raw` is saturated.
        invalid: Output, the input was a NaN: `raw` is 0.
        fmt: The fixed-point format of `raw`.
    """
    width = fmt.width
    layout = to_fixed_layout(fmt)
    field_bits, placement = layout.field_bits, layout.placement
    amount_base, amount_min = layout.amount_base, layout.amount_min
    amount_max = amount_base

    @always_comb
    def convert() -> None:
        exponent = intbv(0)[11:]
        exponent[:] = bits[63:MANTISSA_BITS]
        significand = intbv(0)[SIGNIFICAND_BITS:]
        significand[:] = bits[MANTISSA_BITS:0]
        significand[MANTISSA_BITS] = exponent != 0
        amount = intbv(0, min=amount_min, max=amount_max + 1)
        if exponent == 0:
            amount[:] = amount_base - 1
        else:
            amount[:] = amount_base - exponent
        field = intbv(0)[field_bits:]
        field[:] = significand
        field[:] = field << placement
        if amount > field_bits:
            field[:] = 0
        elif amount >= 0:
            field[:] = field >> amount
        quotient = intbv(0)[width + 1 :]
        quotient[:] = field[field_bits:ROUNDING_BITS]
        if field[ROUNDING_BITS - 1] and (field[ROUNDING_BITS - 1 : 0] != 0 or quotient[0]):
            quotient[:] = quotient + 1
        negative = bool(bits[63])
        # Largest magnitude allowed: 2**(width-1) when negative, 2**(width-1) - 1 otherwise.
        too_large = bool(quotient[width] or quotient[width - 1])
        if negative and not quotient[width] and quotient[width - 1 : 0] == 0:
            too_large = False
        nan = bool(exponent == EXPONENT_ALL_ONES and bits[MANTISSA_BITS:0] != 0)
        saturate = bool(exponent == EXPONENT_ALL_ONES or amount < 0 or too_large)
        magnitude = intbv(0)[width + 1 :]
        if nan:
            magnitude[:] = 0
        elif saturate:
            magnitude[width - 1] = 1
            if not negative:
                magnitude[:] = magnitude - 1
        else:
            magnitude[:] = quotient
        if negative:
            raw.next = -magnitude
        else:
            raw.next = magnitude
        overflow.next = saturate and not nan
        invalid.next = nan

    return convert


@block
def fixed_to_float(raw: SignalLike, bits: SignalLike, fmt: FixedFormat) -> Instances:
    """Fixed point → float64, rounding to nearest with ties to even (combinational).

    Normalizes with a leading-zero count; zero gives +0.0. Every raw value of a valid format
    is a normal float64, so no other special case exists.

    Args:
        raw: Input, the raw integer of `fmt` (signed ``intbv`` of ``fmt.width`` bits).
        bits: Output, 64-bit IEEE-754 pattern (unsigned ``intbv[64:]``).
        fmt: The fixed-point format of `raw`.
    """
    width = fmt.width
    layout = to_float_layout(fmt)
    exponent_base, padded_bits, excess = layout.exponent_base, layout.padded_bits, layout.excess

    @always_comb
    def convert() -> None:
        negative = bool(raw < 0)
        magnitude = intbv(0)[width:]
        if negative:
            magnitude[:] = -raw
        else:
            magnitude[:] = raw
        leading_zeros = intbv(0, min=0, max=width + 1)
        leading_zeros[:] = width
        for i in range(width):
            if magnitude[i]:
                leading_zeros[:] = width - 1 - i
        normalized = intbv(0)[padded_bits:]
        normalized[:] = magnitude
        normalized[:] = normalized << (padded_bits - width)
        normalized[:] = normalized << leading_zeros
        significand = intbv(0)[SIGNIFICAND_BITS + 1 :]
        significand[:] = normalized[padded_bits:excess]
        exponent = intbv(0)[12:]
        exponent[:] = exponent_base - leading_zeros
        if normalized[excess - 1] and (normalized[excess - 1 : 0] != 0 or significand[0]):
            significand[:] = significand + 1
        if significand[SIGNIFICAND_BITS]:
            significand[:] = significand >> 1
            exponent[:] = exponent + 1
        if magnitude == 0:
            bits.next = 0
        else:
            bits.next = concat(negative, exponent[11:0], significand[MANTISSA_BITS:0])

    return convert
