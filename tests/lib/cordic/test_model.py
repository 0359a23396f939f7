"""The CORDIC constants and model against independent arithmetic and math.atan2."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rfc.lib.cordic import CordicConfig, Vectored, vectoring
from rfc.lib.cordic.config import arctan_of_inverse, quarter_pi

#: π in hexadecimal, 32 fraction digits (128 bits): a published constant, not computed here.
PI_HEX = 0x3_243F6A88_85A308D3_13198A2E_03707344


def test_pi_matches_its_published_digits():
    # π/4 · 2**130 is π · 2**128: the published digits, rounded rather than truncated.
    assert quarter_pi(130) - PI_HEX in (0, 1)
    assert CordicConfig(8, 8, 124).pi == (PI_HEX + 8) >> 4


def test_arctangents_satisfy_eulers_identity():
    # π/4 = atan(1/2) + atan(1/3): other inputs to the series than Machin's 5 and 239.
    bits = 200
    assert abs(arctan_of_inverse(2, bits) + arctan_of_inverse(3, bits) - quarter_pi(bits)) <= 1


@given(st.integers(1, 60))
def test_table_entries_are_rounded_arctangents(i):
    table = CordicConfig(8, 61, 52).atan_table
    assert abs(table[i] - math.atan(2.0**-i) * 2**52) <= 0.5 + 1e-3


def test_gain_is_the_product_of_the_stretches():
    config = CordicConfig(16, 30, 40)
    exact = math.prod(math.sqrt(1 + 4.0**-i) for i in range(30))
    assert config.gain(60) / 2**60 == pytest.approx(exact, rel=1e-15)


@st.composite
def configs_and_inputs(draw):
    config = CordicConfig(
        draw(st.integers(4, 72)), draw(st.integers(4, 48)), draw(st.integers(8, 64))
    )
    low, high = -(1 << (config.width - 1)), (1 << (config.width - 1)) - 1
    x, y = draw(st.integers(low, high)), draw(st.integers(low, high))
    return config, x, y


@given(configs_and_inputs())
def test_angle_and_magnitude_are_within_the_iterations_residual(case):
    config, x, y = case
    result = vectoring(x, y, config)
    n, scale = config.iterations, 2.0**config.angle_frac
    length = math.hypot(x, y)
    if length == 0:
        assert result == Vectored(0, 0)
        return
    # Residual angle, table rounding, and x/y truncation seen from the vector's length.
    slack = 2 * n / (length * 2**config.guard)
    bound = math.atan(2.0 ** (1 - n)) + n / scale + slack
    error = abs(math.remainder(result.angle / scale - math.atan2(y, x), math.tau))
    assert error <= bound
    gain = config.gain(60) / 2**60
    assert abs(result.magnitude - gain * length) <= 1 + gain * length * (slack + 2.0**-n)


@pytest.mark.parametrize(
    ("x", "y", "angle"),
    [(0, 0, 0), (5, 0, 0), (-5, 0, "pi"), (-(1 << 15), 0, "pi"), ((1 << 15) - 1, 0, 0)],
)
def test_level_vectors_give_exact_angles(x, y, angle):
    config = CordicConfig(16, 20, 30)
    expected = config.pi if angle == "pi" else angle
    assert vectoring(x, y, config).angle == expected


def test_inputs_beyond_the_width_are_refused():
    with pytest.raises(ValueError, match="does not fit in 8 signed bits"):
        vectoring(128, 0, CordicConfig(8, 8, 10))


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        ((1, 8, 10), "at least 2 bits"),
        ((8, 0, 10), "at least one iteration"),
        ((8, 8, 0), "angle_frac must be at least 1"),
        ((8, 8, 10, -1), "guard_bits cannot be negative"),
    ],
)
def test_impossible_configurations_are_refused(arguments, message):
    with pytest.raises(ValueError, match=message):
        CordicConfig(*arguments)
