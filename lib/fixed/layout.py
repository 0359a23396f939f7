"""Where the bits sit in the hardware float64 ↔ fixed conversions, combinational or pipelined.

Both `rfc.lib.fixed.hdl` and `rfc.lib.fixed.pipeline` shift a float64's significand within a
field and count leading zeros of a fixed-point magnitude; the widths and offsets they need
depend on the format only, and are computed here once.
"""

from __future__ import annotations

from dataclasses import dataclass

from rfc.lib.fixed.format import FixedFormat
from rfc.lib.fixed.ieee754 import (
    EXPONENT_ALL_ONES,
    EXPONENT_BIAS,
    MANTISSA_BITS,
    ROUNDING_BITS,
    SIGNIFICAND_SHIFT,
)

#: A float64's significand with its hidden bit.
SIGNIFICAND_BITS = MANTISSA_BITS + 1


@dataclass(frozen=True)
class ToFixedLayout:
    """The float64 → `fmt` shift.

    The significand placed at the top of a field of ``ROUNDING_BITS + width`` bits and shifted
    right by ``amount = amount_base - max(exponent, 1) + 1`` leaves the value scaled by
    ``2**(frac_bits + ROUNDING_BITS)``, with ROUNDING_BITS below the rounding point; a shift
    beyond the field leaves zero, a negative one means the value is too large.

    Attributes:
        field_bits: The field's width.
        placement: Where the significand's lowest bit sits in the field.
        amount_base: The shift of exponent 1 (and of subnormals) plus one.
        amount_min: The shift of the largest exponent (Inf and NaN).
    """

    field_bits: int
    placement: int
    amount_base: int
    amount_min: int


def to_fixed_layout(fmt: FixedFormat) -> ToFixedLayout:
    """The shift that converts a float64 to `fmt`."""
    field_bits = ROUNDING_BITS + fmt.width
    # amount = (width - 53) - shift with shift = max(exponent, 1) - 1075 + frac_bits.
    amount_base = fmt.width - SIGNIFICAND_BITS + SIGNIFICAND_SHIFT - fmt.frac_bits
    return ToFixedLayout(
        field_bits=field_bits,
        placement=field_bits - SIGNIFICAND_BITS,
        amount_base=amount_base,
        amount_min=amount_base - EXPONENT_ALL_ONES,
    )


@dataclass(frozen=True)
class ToFloatLayout:
    """The `fmt` → float64 normalization.

    Attributes:
        exponent_base: The biased exponent of a value whose leading one is the magnitude's top
            bit (subtract the leading zeros).
        padded_bits: The normalized magnitude's width: zeros are appended below narrow values
            so that a round bit and a sticky bit always exist.
        excess: Bits of the normalized magnitude below the significand's.
    """

    exponent_base: int
    padded_bits: int
    excess: int


def to_float_layout(fmt: FixedFormat) -> ToFloatLayout:
    """The normalization that converts `fmt` to a float64."""
    padded_bits = max(fmt.width, SIGNIFICAND_BITS + 2)
    return ToFloatLayout(
        exponent_base=fmt.width - 1 - fmt.frac_bits + EXPONENT_BIAS,
        padded_bits=padded_bits,
        excess=padded_bits - SIGNIFICAND_BITS,
    )
