"""The float64 ↔ fixed models against exact rational arithmetic."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rfc.lib.fixed import (
    FixedFormat,
    ToFixed,
    bits_to_float,
    fixed_to_float,
    float_to_bits,
    float_to_fixed,
)
from tests.lib.fixed.strategies import floats_near, formats

Q2_53 = FixedFormat(55, 53)


def exact_to_fixed(value: float, fmt: FixedFormat) -> ToFixed:
    """Round to nearest, ties to even (Python's round of a Fraction), then saturate."""
    if math.isnan(value):
        return ToFixed(0, invalid=True)
    if math.isinf(value):
        return ToFixed(fmt.min_raw if value < 0 else fmt.max_raw, overflow=True)
    raw = round(Fraction(value) * (1 << fmt.frac_bits))
    if raw > fmt.max_raw:
        return ToFixed(fmt.max_raw, overflow=True)
    if raw < fmt.min_raw:
        return ToFixed(fmt.min_raw, overflow=True)
    return ToFixed(raw)


@given(st.data())
def test_float_to_fixed_rounds_to_nearest_even_and_saturates(data):
    fmt = data.draw(formats())
    value = data.draw(floats_near(fmt))
    assert float_to_fixed(float_to_bits(value), fmt) == exact_to_fixed(value, fmt)


@given(st.data())
def test_fixed_to_float_rounds_to_nearest_even(data):
    fmt = data.draw(formats())
    raw = data.draw(st.integers(fmt.min_raw, fmt.max_raw))
    # int / int is correctly rounded in Python: the exact oracle.
    assert bits_to_float(fixed_to_float(raw, fmt)) == raw / (1 << fmt.frac_bits)


@given(st.data())
def test_narrow_formats_round_trip_exactly(data):
    fmt = data.draw(formats(max_width=54))
    raw = data.draw(st.integers(fmt.min_raw, fmt.max_raw))
    assert float_to_fixed(fixed_to_float(raw, fmt), fmt) == ToFixed(raw)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (float("nan"), ToFixed(0, invalid=True)),
        (float("inf"), ToFixed(Q2_53.max_raw, overflow=True)),
        (float("-inf"), ToFixed(Q2_53.min_raw, overflow=True)),
        (2.0, ToFixed(Q2_53.max_raw, overflow=True)),
        (-2.0, ToFixed(Q2_53.min_raw)),
        (-0.0, ToFixed(0)),
        (5e-324, ToFixed(0)),
        (1.0, ToFixed(1 << 53)),
        (2.5 * 2.0**-53, ToFixed(2)),
        (3.5 * 2.0**-53, ToFixed(4)),
        (-2.5 * 2.0**-53, ToFixed(-2)),
    ],
)
def test_documented_special_cases(value, expected):
    assert float_to_fixed(float_to_bits(value), Q2_53) == expected


def test_fixed_to_float_gives_positive_zero_and_rejects_out_of_range():
    assert fixed_to_float(0, Q2_53) == 0
    with pytest.raises(ValueError, match="outside"):
        fixed_to_float(Q2_53.max_raw + 1, Q2_53)


@pytest.mark.parametrize(
    ("width", "frac_bits", "message"),
    [
        (1, 0, "at least 2 bits"),
        (8, -1, "frac_bits must lie in 0..1022"),
        (8, 1023, "frac_bits must lie in 0..1022"),
        (1030, 2, "exceed float64's exponent range"),
    ],
)
def test_formats_float64_cannot_hold_are_refused(width, frac_bits, message):
    with pytest.raises(ValueError, match=message):
        FixedFormat(width, frac_bits)
