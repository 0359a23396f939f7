"""The conversions' bit layout against powers of two, whose float64 fields are known exactly."""

from __future__ import annotations

import math

import pytest

from rfc.lib.fixed import FixedFormat
from rfc.lib.fixed.ieee754 import EXPONENT_BIAS, MANTISSA_BITS, ROUNDING_BITS
from rfc.lib.fixed.layout import to_fixed_layout, to_float_layout

FORMATS = [FixedFormat(50, 44), FixedFormat(46, 44), FixedFormat(64, 60), FixedFormat(8, 0)]


@pytest.mark.parametrize("fmt", FORMATS, ids=str)
def test_a_power_of_two_lands_on_its_bit_of_the_field(fmt):
    layout = to_fixed_layout(fmt)
    for k in range(-fmt.frac_bits, fmt.int_bits - 1):
        exponent = k + EXPONENT_BIAS  # 2**k as a float64: significand 1.0
        amount = layout.amount_base - exponent
        placed = (1 << MANTISSA_BITS) << layout.placement
        assert 0 <= amount <= layout.field_bits
        assert placed >> amount == 1 << (k + fmt.frac_bits + ROUNDING_BITS)
    # the largest exponent (Inf, NaN) shifts left: too large for any format
    assert layout.amount_min == layout.amount_base - 0x7FF < 0


@pytest.mark.parametrize("fmt", FORMATS, ids=str)
def test_a_power_of_two_gets_its_exponent(fmt):
    layout = to_float_layout(fmt)
    for bit in range(fmt.width - 1):
        leading_zeros = fmt.width - 1 - bit
        value = math.ldexp(1.0, bit - fmt.frac_bits)
        assert layout.exponent_base - leading_zeros == math.frexp(value)[1] - 1 + EXPONENT_BIAS
    assert layout.padded_bits - layout.excess == MANTISSA_BITS + 1
    assert layout.excess >= 2  # a round bit and a sticky bit below the significand
