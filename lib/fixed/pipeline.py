"""Float64 ↔ fixed point as pipelines of short stages: a value every cycle at 100 MHz and more.

The combinational blocks of `rfc.lib.fixed.hdl` do a whole conversion between two registers:
exponent, a 100-bit barrel shift, a rounding carry chain and a negation in one cycle, 8.4 ns of
7-series cells for a Q2.44 result, beyond the 5 ns a 100 MHz clock allows before routing. Here
the same steps are cut into stages of about one carry chain or three LUT levels each, with the
bits of `rfc.lib.fixed.ieee754`. Both are datapaths without handshakes, like
`rfc.lib.cordic.hdl.cordic_pipeline`: every register loads on the cycles `advance` is high,
and a value comes out `FLOAT_TO_FIXED_STAGES` (`FIXED_TO_FLOAT_STAGES`) advancing cycles after
it went in, on registers. `rfc.lib.arith.convert_hdl` wraps them with valid/ready handshakes.
The registers hold data only (no reset): a valid bit travelling beside them says what they mean.
"""

from __future__ import annotations

from myhdl import Signal, always_seq, block, concat, intbv

from rfc.lib.fixed.format import FixedFormat
from rfc.lib.fixed.ieee754 import EXPONENT_ALL_ONES, MANTISSA_BITS, ROUNDING_BITS
from rfc.lib.fixed.layout import SIGNIFICAND_BITS, to_fixed_layout, to_float_layout
from rfc.lib.types import Instances, SignalLike

#: Registers of `float_to_fixed_pipeline`: decode, coarse shift, fine shift, round, sign.
FLOAT_TO_FIXED_STAGES = 5
#: Registers of `fixed_to_float_pipeline`: magnitude, leading zeros, normalize, round and pack.
FIXED_TO_FLOAT_STAGES = 4
#: The barrel shift is split in two: by multiples of 2**FINE_BITS, then by the rest.
FINE_BITS = 3


def _unsigned(bits: int) -> Signal:
    return Signal(intbv(0)[bits:])


def _ranged(top: int) -> Signal:
    return Signal(intbv(0, min=0, max=top + 1))


@block
def float_to_fixed_pipeline(
    clk: SignalLike,
    advance: SignalLike,
    bits: SignalLike,
    raw: SignalLike,
    overflow: SignalLike,
    invalid: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """Float64 → `fmt`, ties to even, saturating: `ieee754.float_to_fixed` in five stages.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`.

    Args:
        bits: Input, 64-bit IEEE-754 pattern.
        raw: Output register, the raw integer of `fmt` (signed ``fmt.width`` bits).
        overflow: Output register, the input lay outside `fmt` or was ±Inf: `raw` saturated.
        invalid: Output register, the input was a NaN: `raw` is 0.
        fmt: The fixed-point format of `raw`.
    """
    width = fmt.width
    layout = to_fixed_layout(fmt)
    field_bits, placement = layout.field_bits, layout.placement
    amount_base, amount_min = layout.amount_base, layout.amount_min

    # Stage 1, decode: sign, significand, shift (clamped to the field), early flags.
    sign1, nan1, saturate1 = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    significand1 = _unsigned(SIGNIFICAND_BITS)
    coarse1, fine1 = _ranged(field_bits), _ranged((1 << FINE_BITS) - 1)
    # Stage 2, shifted by the multiple of 2**FINE_BITS; stage 3, by the rest.
    sign2, nan2, saturate2 = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    field2, fine2 = _unsigned(field_bits), _ranged((1 << FINE_BITS) - 1)
    sign3, nan3, saturate3 = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    quotient3, round3, sticky3 = _unsigned(width), Signal(bool(0)), Signal(bool(0))
    # Stage 4, rounded magnitude (one bit wider: rounding may carry out).
    sign4, nan4, saturate4 = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    magnitude4 = _unsigned(width + 1)

    @always_seq(clk.posedge, reset=None)
    def decode() -> None:
        if advance:
            exponent = intbv(0)[11:]
            exponent[:] = bits[63:MANTISSA_BITS]
            amount = intbv(0, min=amount_min, max=amount_base + 1)
            if exponent == 0:
                amount[:] = amount_base - 1
            else:
                amount[:] = amount_base - exponent
            shift = intbv(0, min=0, max=field_bits + 1)
            if amount > field_bits:
                shift[:] = field_bits
            elif amount >= 0:
                shift[:] = amount
            coarse = intbv(0, min=0, max=field_bits + 1)
            coarse[:] = shift
            coarse[FINE_BITS:0] = 0
            significand = intbv(0)[SIGNIFICAND_BITS:]
            significand[:] = bits[MANTISSA_BITS:0]
            significand[MANTISSA_BITS] = exponent != 0
            sign1.next = bits[63]
            significand1.next = significand
            coarse1.next = coarse
            fine1.next = shift[FINE_BITS:0]
            nan1.next = exponent == EXPONENT_ALL_ONES and bits[MANTISSA_BITS:0] != 0
            saturate1.next = exponent == EXPONENT_ALL_ONES or amount < 0

    # Each stage copies the flags beside its data: a `data_delay` per flag is the same registers
    # in an array, which tools/check_hdl_equivalence.py could not prove the same circuit.
    @always_seq(clk.posedge, reset=None)
    def coarse_shift() -> None:
        if advance:
            field = intbv(0)[field_bits:]
            field[:] = significand1
            field[:] = field << placement
            field2.next = field >> coarse1
            fine2.next = fine1
            sign2.next = sign1
            nan2.next = nan1
            saturate2.next = saturate1

    @always_seq(clk.posedge, reset=None)
    def fine_shift() -> None:
        if advance:
            field = intbv(0)[field_bits:]
            field[:] = field2 >> fine2
            quotient3.next = field[field_bits:ROUNDING_BITS]
            round3.next = field[ROUNDING_BITS - 1]
            sticky3.next = field[ROUNDING_BITS - 1 : 0] != 0
            sign3.next = sign2
            nan3.next = nan2
            saturate3.next = saturate2

    @always_seq(clk.posedge, reset=None)
    def round_even() -> None:
        if advance:
            if round3 and (sticky3 or quotient3[0]):
                magnitude4.next = quotient3 + 1
            else:
                magnitude4.next = quotient3
            sign4.next = sign3
            nan4.next = nan3
            saturate4.next = saturate3

    @always_seq(clk.posedge, reset=None)
    def apply_sign() -> None:
        if advance:
            # Largest magnitude allowed: 2**(width-1) when negative, 2**(width-1) - 1 otherwise.
            too_large = bool(magnitude4[width] or magnitude4[width - 1])
            if sign4 and not magnitude4[width] and magnitude4[width - 1 : 0] == 0:
                too_large = False
            # The negation runs beside the decision, which only picks its result.
            negated = intbv(0, min=-(1 << (width + 1)), max=1 << (width + 1))
            if sign4:
                negated[:] = -magnitude4
            else:
                negated[:] = magnitude4
            # The saturated raw value's bits: 100…0 when negative, 011…1 otherwise.
            limit = intbv(0)[width:]
            for i in range(width - 1):
                limit[i] = not sign4
            limit[width - 1] = sign4
            if nan4:
                raw.next = 0
            elif saturate4 or too_large:
                raw.next = limit.signed()
            else:
                raw.next = negated
            overflow.next = (saturate4 or too_large) and not nan4
            invalid.next = nan4

    return decode, coarse_shift, fine_shift, round_even, apply_sign


@block
def fixed_to_float_pipeline(
    clk: SignalLike, advance: SignalLike, raw: SignalLike, bits: SignalLike, fmt: FixedFormat
) -> Instances:
    """`fmt` → float64, ties to even: `ieee754.fixed_to_float` in four stages.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`.

    Args:
        raw: Input, the raw integer of `fmt` (signed ``fmt.width`` bits).
        bits: Output register, the 64-bit IEEE-754 pattern (zero gives +0.0).
        fmt: The fixed-point format of `raw`.
    """
    width = fmt.width
    layout = to_float_layout(fmt)
    exponent_base, padded_bits, excess = layout.exponent_base, layout.padded_bits, layout.excess

    negative1, negative2, negative3 = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    magnitude1, magnitude2 = _unsigned(width), _unsigned(width)
    zeros2 = _ranged(width)
    normalized3 = _unsigned(padded_bits)
    exponent3, zero3 = _unsigned(12), Signal(bool(0))

    @always_seq(clk.posedge, reset=None)
    def magnitude() -> None:
        if advance:
            negative1.next = raw < 0
            if raw < 0:
                magnitude1.next = -raw
            else:
                magnitude1.next = raw

    @always_seq(clk.posedge, reset=None)
    def leading_zeros() -> None:
        if advance:
            count = intbv(0, min=0, max=width + 1)
            count[:] = width
            for i in range(width):
                if magnitude1[i]:
                    count[:] = width - 1 - i
            zeros2.next = count
            magnitude2.next = magnitude1
            negative2.next = negative1

    @always_seq(clk.posedge, reset=None)
    def normalize() -> None:
        if advance:
            normalized = intbv(0)[padded_bits:]
            normalized[:] = magnitude2
            normalized[:] = normalized << (padded_bits - width)
            normalized3.next = normalized << zeros2
            exponent3.next = exponent_base - zeros2
            zero3.next = zeros2 == width
            negative3.next = negative2

    @always_seq(clk.posedge, reset=None)
    def round_and_pack() -> None:
        if advance:
            significand = intbv(0)[SIGNIFICAND_BITS + 1 :]
            significand[:] = normalized3[padded_bits:excess]
            exponent = intbv(0)[12:]
            exponent[:] = exponent3
            if normalized3[excess - 1] and (normalized3[excess - 1 : 0] != 0 or significand[0]):
                significand[:] = significand + 1
            if significand[SIGNIFICAND_BITS]:
                significand[:] = significand >> 1
                exponent[:] = exponent + 1
            if zero3:
                bits.next = 0
            else:
                bits.next = concat(negative3, exponent[11:0], significand[MANTISSA_BITS:0])

    return magnitude, leading_zeros, normalize, round_and_pack
