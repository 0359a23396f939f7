"""Bit-exact models of the float64 ↔ fixed-point conversions the hardware blocks perform.

These are the references the MyHDL blocks in `rfc.lib.fixed.hdl` are tested against, bit for
bit; they are themselves checked against exact rational arithmetic (`fractions.Fraction`).
Floats travel as their 64-bit IEEE-754 patterns (ints), the way they sit on a bus.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

from rfc.lib.fixed.format import FixedFormat

MANTISSA_BITS = 52
EXPONENT_BIAS = 1023
EXPONENT_ALL_ONES = 0x7FF
#: Where the point sits in the 53-bit significand of a float64 relative to its raw exponent:
#: a normal float is ``significand * 2**(exponent - SIGNIFICAND_SHIFT)``.
SIGNIFICAND_SHIFT = EXPONENT_BIAS + MANTISSA_BITS
#: Fraction bits kept below the rounding point while converting float → fixed: enough that a
#: 53-bit significand shifted past them leaves only zeros (round bit and sticky bits included).
ROUNDING_BITS = 54
#: The quiet NaN pattern fixed → float never produces, but users compare against.
QUIET_NAN = 0x7FF8_0000_0000_0000


def float_to_bits(value: float) -> int:
    """The IEEE-754 float64 bit pattern of a Python float."""
    bits: int = struct.unpack("<Q", struct.pack("<d", value))[0]
    return bits


def bits_to_float(bits: int) -> float:
    """The Python float of an IEEE-754 float64 bit pattern."""
    value: float = struct.unpack("<d", struct.pack("<Q", bits))[0]
    return value


@dataclass(frozen=True)
class ToFixed:
    """The result of a float64 → fixed conversion.

    Attributes:
        raw: The fixed-point raw integer (0 for NaN, saturated when `overflow`).
        overflow: The value lay outside the format (±Inf included) and was saturated.
        invalid: The input was a NaN.
    """

    raw: int
    overflow: bool = False
    invalid: bool = False


def float_to_fixed(bits: int, fmt: FixedFormat) -> ToFixed:
    """Convert a float64 bit pattern to `fmt`, rounding to nearest with ties to even.

    Subnormals are exact inputs like any other; -0.0 gives 0. Values beyond the format saturate
    to its most negative or most positive raw value and set `overflow` (so does ±Inf); a NaN
    gives 0 and sets `invalid`.
    """
    negative = bool(bits >> 63)
    exponent = (bits >> MANTISSA_BITS) & EXPONENT_ALL_ONES
    fraction = bits & ((1 << MANTISSA_BITS) - 1)
    saturated = fmt.min_raw if negative else fmt.max_raw
    if exponent == EXPONENT_ALL_ONES:
        return ToFixed(0, invalid=True) if fraction else ToFixed(saturated, overflow=True)
    significand = fraction | (1 << MANTISSA_BITS) if exponent else fraction
    # value * 2**frac_bits == significand * 2**shift
    shift = max(exponent, 1) - SIGNIFICAND_SHIFT + fmt.frac_bits
    if shift > fmt.width - MANTISSA_BITS - 1:
        # A normal significand (subnormals never get here) reaches 2**width: out of range.
        return ToFixed(saturated, overflow=True)
    magnitude = _round_half_even(significand, shift)
    limit = -fmt.min_raw if negative else fmt.max_raw
    if magnitude > limit:
        return ToFixed(saturated, overflow=True)
    return ToFixed(-magnitude if negative else magnitude)


def _round_half_even(significand: int, shift: int) -> int:
    """``round(significand * 2**shift)`` with ties to even, as the hardware computes it."""
    if shift >= 0:
        return significand << shift
    kept = significand << ROUNDING_BITS >> min(-shift, ROUNDING_BITS + MANTISSA_BITS + 1)
    quotient = kept >> ROUNDING_BITS
    round_bit = (kept >> (ROUNDING_BITS - 1)) & 1
    sticky = kept & ((1 << (ROUNDING_BITS - 1)) - 1) != 0
    return quotient + (round_bit & (sticky | quotient & 1))


def fixed_to_float(raw: int, fmt: FixedFormat) -> int:
    """Convert a raw fixed-point integer of `fmt` to a float64 bit pattern, ties to even.

    Every raw value of a valid format is a normal float64 or zero (+0.0), so there is no
    overflow, underflow or NaN: only rounding when the value has more than 53 significant bits.
    """
    if not fmt.min_raw <= raw <= fmt.max_raw:
        raise ValueError(f"raw value {raw} lies outside {fmt}")
    if raw == 0:
        return 0
    negative = raw < 0
    magnitude = -raw if negative else raw
    length = magnitude.bit_length()
    excess = length - (MANTISSA_BITS + 1)
    if excess > 0:
        significand = magnitude >> excess
        round_bit = (magnitude >> (excess - 1)) & 1
        sticky = magnitude & ((1 << (excess - 1)) - 1) != 0
        significand += round_bit & (sticky | significand & 1)
        if significand >> (MANTISSA_BITS + 1):
            significand >>= 1
            length += 1
    else:
        significand = magnitude << -excess
    exponent = length - 1 - fmt.frac_bits + EXPONENT_BIAS
    fraction = significand & ((1 << MANTISSA_BITS) - 1)
    return (int(negative) << 63) | (exponent << MANTISSA_BITS) | fraction
