"""Fixed point ↔ IEEE-754 float64: a number format, bit-exact models and MyHDL blocks.

`FixedFormat` names a signed two's-complement format; `float_to_fixed` / `fixed_to_float` in
`ieee754` are the models (float64 travels as its 64-bit pattern), and the same names in `hdl`
are the combinational MyHDL blocks that match them bit for bit; `pipeline` holds the same
conversions cut into short register stages (a value every cycle at 100 MHz and beyond);
`layout` computes where the bits sit for both.
"""

from rfc.lib.fixed.format import FixedFormat
from rfc.lib.fixed.ieee754 import (
    QUIET_NAN,
    ToFixed,
    bits_to_float,
    fixed_to_float,
    float_to_bits,
    float_to_fixed,
)

__all__ = [
    "QUIET_NAN",
    "FixedFormat",
    "ToFixed",
    "bits_to_float",
    "fixed_to_float",
    "float_to_bits",
    "float_to_fixed",
]
