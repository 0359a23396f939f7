"""Quaternion → Euler angles accelerator (paper use case 7.1.1): MyHDL core and its references.

Point x = roll, y = pitch, z = yaw: intrinsic Z-Y-X angles by the usual formulas

    roll  = atan2(2(wx + yz), 1 - 2(x² + y²))
    pitch = asin(clamp(2(wy - zx), -1, 1))
    yaw   = atan2(2(wz + xy), 1 - 2(y² + z²))

The core works in fixed point. The four components become Q2.53 (`COMPONENT`); one multiplier,
shared over twelve cycles, forms the nine products exactly (106 fraction bits) and sums them,
a third of each sum's bits per cycle, into the arguments of the two atan2s and into
sin(pitch). Two iterative CORDICs in vectoring mode give roll and yaw, and the lengths of their
vectors, each cos(pitch) for a unit quaternion; the roll CORDIC then gives
pitch = atan2(sin(pitch), cos(pitch)) from their mean, which stays accurate near ±π/2 where an
arcsine does not. Angles are Q3.60 radians turned into float64.

Three functions describe the same mapping: `quat_to_euler` (the hardware), `reference` (the same
integer steps in Python, bit for bit) and `numpy_reference` (the double-precision formulas).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from myhdl import Signal, always_comb, always_seq, block, enum, intbv
from numpy.typing import ArrayLike, NDArray
from split_accumulator import ACCUMULATE_CYCLES, split_accumulator

from rfc.lib.arith.mac_hdl import exact_multiply, exact_multiply_stages
from rfc.lib.cordic import CordicConfig, vectoring
from rfc.lib.cordic.hdl import cordic_vectoring
from rfc.lib.fixed import QUIET_NAN, FixedFormat, fixed_to_float, float_to_fixed
from rfc.lib.fixed.pipeline import (
    FIXED_TO_FLOAT_STAGES,
    FLOAT_TO_FIXED_STAGES,
    fixed_to_float_pipeline,
    float_to_fixed_pipeline,
)


@dataclass(frozen=True)
class Precision:
    """The number formats of one implementation; `reference` follows them bit for bit.

    Attributes:
        component: The quaternion's components, Q2.f: unit quaternions lie in [-1, 1], and
            their largest component, at least 1/2, converts exactly.
        cordic: The CORDICs: inputs Q6.`cordic_frac` (the atan2 arguments lie in [-15, 16]
            for any component in range), angles Q3.`angle_frac` radians.
        cordic_frac: Fraction bits of the CORDIC inputs (``cordic.width - 6``).
    """

    component: FixedFormat
    cordic: CordicConfig
    cordic_frac: int

    @property
    def product_frac(self) -> int:
        """Fraction bits of the exact products and their sums."""
        return 2 * self.component.frac_bits

    @property
    def sum_width(self) -> int:
        """Bits of the exact sums (values in [-16, 16))."""
        return self.product_frac + 5

    @property
    def sin_frac(self) -> int:
        """sin(pitch) is rounded to Q6.`sin_frac`, a word as wide as a component."""
        return self.component.width - 6

    @property
    def half_gain_frac(self) -> int:
        """gain/2 is Q1.`half_gain_frac`, a word as wide as a component."""
        return self.component.width - 1

    @property
    def half_gain(self) -> int:
        """The pitch CORDIC's y input must carry the gain its x input (a magnitude) has."""
        return self.cordic.gain(self.half_gain_frac - 1)

    @property
    def angle(self) -> FixedFormat:
        """The angles out of the CORDICs, before float64."""
        return FixedFormat(self.cordic.angle_width, self.cordic.angle_frac)


#: The small iterative core: Q2.53 components; 40 iterations leave about 2e-12 rad.
ITERATIVE = Precision(FixedFormat(55, 53), CordicConfig(width=64, iterations=40, angle_frac=60), 58)
#: The pipelined core: Q2.40 components, 38 iterations; within 2e-10 rad of NumPy (docs).
PIPELINED = Precision(FixedFormat(46, 44), CordicConfig(width=50, iterations=38, angle_frac=46), 44)
COMPONENT = ITERATIVE.component
PRODUCT_FRAC = ITERATIVE.product_frac
SUM_WIDTH = ITERATIVE.sum_width
CORDIC = ITERATIVE.cordic
CORDIC_FRAC = ITERATIVE.cordic_frac
ANGLE = ITERATIVE.angle
#: The pitch CORDIC's x input is the mean length, gain·cos(pitch), halved to fit its width; its
#: y input must carry the same gain: sin(pitch) (Q6.49) times gain/2 (Q1.54) in the shared
#: multiplier.
SIN_FRAC = ITERATIVE.sin_frac
HALF_GAIN_FRAC = ITERATIVE.half_gain_frac
HALF_GAIN = ITERATIVE.half_gain

#: Register stages between issuing a product and summing it: the operands, then the exact
#: product in DSP48E1-sized limbs and a registered adder tree (`exact_multiply`), so that no
#: path runs through a wide multiply and its sum at once.
MULTIPLY_PIPELINE = 1 + exact_multiply_stages(COMPONENT.width, COMPONENT.width)
#: Products issued one per cycle, by their operands: components x, y, z, w, then sin(pitch) and
#: gain/2. wy and zx come first, so that sin(pitch) is summed when the twelfth product, its
#: scaling, needs it (the two issued before it are not used). The tables run on past the tenth
#: entry (the step counter does; unused).
X, Y, Z, W, SIN, GAIN = range(6)
MULTIPLY_CYCLES = 12
_STEPS = MULTIPLY_CYCLES + MULTIPLY_PIPELINE + 1
FIRST_OPERANDS = (W, Z, W, Y, X, Y, Z, W, X) + (SIN,) * (_STEPS - 9)
SECOND_OPERANDS = (Y, X, X, Z, X, Y, Z, Z, Y) + (GAIN,) * (_STEPS - 9)
# sin(pitch), summed from the first two products, must be in its register when issued (step
# MULTIPLY_CYCLES - 1): product 1 is summed at step MULTIPLY_PIPELINE + 1
assert MULTIPLY_PIPELINE + 1 + ACCUMULATE_CYCLES <= MULTIPLY_CYCLES - 1
#: Cycles from the input handshake until `out_valid` is high: the products, a cycle in which
#: the roll and yaw CORDICs' inputs are rounded from the sums (they are registered twice:
#: rounded, then offset by the unit), two CORDIC passes (roll and yaw together, then pitch),
#: each with a start and a capture cycle, and the angles' conversion to float64.
LATENCY = (
    MULTIPLY_CYCLES
    + MULTIPLY_PIPELINE
    + 1
    + 2 * (CORDIC.iterative_latency + 2)
    + FIXED_TO_FLOAT_STAGES
)
#: One quaternion is in flight: after LATENCY cycles the result is offered for at least one
#: cycle; the core sees the next quaternion on the cycle after the result was taken and takes
#: it once its components are through the float64 → fixed conversion.
INITIATION_INTERVAL = LATENCY + 2 + FLOAT_TO_FIXED_STAGES


def _round(value: int, drop: int) -> int:
    """Drop `drop` low bits, rounding half up (the hardware adds 1 at the last kept bit's half)."""
    return ((value >> (drop - 1)) + 1) >> 1


def reference(
    x: int, y: int, z: int, w: int, precision: Precision = ITERATIVE
) -> tuple[int, int, int]:
    """A core's results, bit for bit, from float64 bit patterns: (roll, pitch, yaw) patterns.

    `precision` names the core: `ITERATIVE` (`quat_to_euler`) or `PIPELINED`
    (`quat_to_euler_pipelined.quat_to_euler_pipelined`); both take the same integer steps.
    A component that is NaN, infinite or outside [-2, 2) makes all three results a quiet NaN.
    """
    converted = [float_to_fixed(bits, precision.component) for bits in (x, y, z, w)]
    if any(c.overflow or c.invalid for c in converted):
        return QUIET_NAN, QUIET_NAN, QUIET_NAN
    qx, qy, qz, qw = (c.raw for c in converted)
    cordic, product_frac = precision.cordic, precision.product_frac
    sin_half = qw * qy - qz * qx
    drop = product_frac - precision.cordic_frac
    one = 1 << precision.cordic_frac
    roll = vectoring(
        one + _round(-2 * (qx * qx + qy * qy), drop), _round(2 * (qw * qx + qy * qz), drop), cordic
    )
    yaw = vectoring(
        one + _round(-2 * (qy * qy + qz * qz), drop), _round(2 * (qw * qz + qx * qy), drop), cordic
    )
    sin_pitch = _round(2 * sin_half, product_frac - precision.sin_frac)
    scaled_sin = _round(
        sin_pitch * precision.half_gain,
        precision.sin_frac + precision.half_gain_frac - precision.cordic_frac,
    )
    pitch = vectoring((roll.magnitude + yaw.magnitude) >> 2, scaled_sin, cordic)
    return tuple(fixed_to_float(angle.angle, precision.angle) for angle in (roll, pitch, yaw))


def numpy_reference(quaternions: ArrayLike) -> NDArray[np.float64]:
    """Roll, pitch, yaw in double precision by the usual formulas, for (..., 4) x, y, z, w."""
    q = np.asarray(quaternions, dtype=np.float64)
    x, y, z, w = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1, 1))
    yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return np.stack([roll, pitch, yaw], axis=-1)


def _signed(bits: int) -> Signal:
    return Signal(intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1)))


@block
def quat_to_euler(clk, rst, x, y, z, w, in_valid, in_ready, roll, pitch, yaw, out_valid, out_ready):
    """Quaternion (x, y, z, w) → Euler angles (roll, pitch, yaw), float64 in and out.

    Latency `LATENCY` (188) cycles from the input handshake to `out_valid`, the same for every
    input; one quaternion in flight, so the initiation interval is `INITIATION_INTERVAL` (195)
    cycles when results are taken at once. The float64 ↔ fixed conversions are pipelines of
    short stages (`rfc.lib.fixed.pipeline`), so that no path runs through a whole conversion:
    the core takes a quaternion (`in_ready`) only once its components are through them, so
    they must stay on the inputs while `in_valid` is high, as the handshake requires. Results
    stay on the outputs until taken (`out_valid` and `out_ready` high on a rising edge).

    Accuracy on unit quaternions (docs/accelerators.md): within 2e-12 rad of NumPy's
    double-precision formulas, and within 5e-9 rad where pitch is 1e-7 to 1e-3 rad from ±π/2;
    roll and yaw lose precision like 1e-16 / cos(pitch) there, as the formulas do in any
    arithmetic, and at gimbal lock only pitch is defined. A NaN, an infinity or a component
    outside [-2, 2) gives quiet NaNs.

    Args:
        clk: Clock.
        rst: Synchronous reset (``ResetSignal``).
        x: Input, float64 bit pattern (``intbv[64:]``); likewise `y`, `z`, `w`.
        y: Input component.
        z: Input component.
        w: Input component (scalar part).
        in_valid: Input, x/y/z/w hold a quaternion.
        in_ready: Output, the core takes the quaternion on this cycle when `in_valid` is high.
        roll: Output, float64 bit pattern, radians in [-π, π]; `pitch` in [-π/2, π/2], `yaw`
            in [-π, π].
        pitch: Output angle.
        yaw: Output angle.
        out_valid: Output, roll/pitch/yaw hold a result.
        out_ready: Input, the consumer takes the result on this cycle.
    """
    state_t = enum(
        "IDLE", "CONVERT", "PRODUCTS", "ROUND", "ROLL_YAW_START", "ROLL_YAW_BUSY", "PITCH_START",
        "PITCH_BUSY", "TO_FLOAT", "DONE",
    )  # fmt: skip
    state = Signal(state_t.IDLE)
    cx, cy, cz, cw = (COMPONENT.signal() for _ in range(4))
    over_x, over_y, over_z, over_w = (Signal(bool(0)) for _ in range(4))
    nan_x, nan_y, nan_z, nan_w = (Signal(bool(0)) for _ in range(4))
    always_on = Signal(bool(1))
    converters = [
        float_to_fixed_pipeline(clk, always_on, x, cx, over_x, nan_x, COMPONENT),
        float_to_fixed_pipeline(clk, always_on, y, cy, over_y, nan_y, COMPONENT),
        float_to_fixed_pipeline(clk, always_on, z, cz, over_z, nan_z, COMPONENT),
        float_to_fixed_pipeline(clk, always_on, w, cw, over_w, nan_w, COMPONENT),
    ]
    # cycles the components have been on the inputs, up to a conversion's stages
    waited = Signal(intbv(0, min=0, max=FLOAT_TO_FIXED_STAGES + 1))
    converted = FLOAT_TO_FIXED_STAGES - 1
    to_float_last = FIXED_TO_FLOAT_STAGES - 1
    qx, qy, qz, qw = (COMPONENT.signal() for _ in range(4))
    out_of_range = Signal(bool(0))
    bad_input = Signal(bool(0))

    # Shared multiplier: operands, product, five sums and the scaled sin(pitch).
    step = Signal(intbv(0, min=0, max=_STEPS))
    operand_a = COMPONENT.signal()
    operand_b = COMPONENT.signal()
    product = _signed(2 * COMPONENT.width)
    # x² + y² and y² + z² are summed negated: -sum rounded is then one carry chain, where
    # negating the sum and rounding it were two in a row (5.0 ns, the core's critical path)
    sum_sin, sum_roll_b, negated_roll_a, negated_yaw_a, sum_yaw_b = (
        _signed(SUM_WIDTH) for _ in range(5)
    )
    clear_sums = Signal(bool(0))
    add_sin, subtract_sin, add_roll_b, subtract_roll_a, subtract_yaw_a, add_yaw_b = (
        Signal(bool(0)) for _ in range(6)
    )
    never = Signal(bool(0))
    scaled_sin = _signed(2 * COMPONENT.width)
    sin_pitch = COMPONENT.signal()
    first, second = Signal(intbv(0, min=0, max=6)), Signal(intbv(0, min=0, max=6))
    selected_a, selected_b = COMPONENT.signal(), COMPONENT.signal()
    operands = (qx, qy, qz, qw, sin_pitch)
    selectors = [
        select_operand(first, *operands, selected_a),
        select_operand(second, *operands, selected_b),
    ]

    # CORDICs: A does roll then pitch, B does yaw.
    a_in_valid, a_in_ready, a_out_valid, a_out_ready = (Signal(bool(0)) for _ in range(4))
    b_in_valid, b_in_ready, b_out_valid, b_out_ready = (Signal(bool(0)) for _ in range(4))
    a_x, a_y, b_x, b_y = (_signed(CORDIC.width) for _ in range(4))
    a_rounded, b_rounded, a_roll, b_roll, pitch_y = (_signed(CORDIC.width) for _ in range(5))
    a_angle, b_angle = _signed(CORDIC.angle_width), _signed(CORDIC.angle_width)
    a_magnitude = Signal(intbv(0)[CORDIC.magnitude_width :])
    b_magnitude = Signal(intbv(0)[CORDIC.magnitude_width :])
    cordic_a = cordic_vectoring(
        clk,
        rst,
        a_in_valid,
        a_in_ready,
        a_x,
        a_y,
        a_out_valid,
        a_out_ready,
        a_angle,
        a_magnitude,
        CORDIC,
    )
    cordic_b = cordic_vectoring(
        clk,
        rst,
        b_in_valid,
        b_in_ready,
        b_x,
        b_y,
        b_out_valid,
        b_out_ready,
        b_angle,
        b_magnitude,
        CORDIC,
    )
    # Sum of both vectors' lengths: 2·gain·cos(pitch) for a unit quaternion.
    lengths = Signal(intbv(0)[CORDIC.magnitude_width + 1 :])
    roll_angle, pitch_angle, yaw_angle = (ANGLE.signal() for _ in range(3))
    roll_bits, pitch_bits, yaw_bits = (Signal(intbv(0)[64:]) for _ in range(3))
    to_float = [
        fixed_to_float_pipeline(clk, always_on, angle, bits, ANGLE)
        for angle, bits in zip(
            (roll_angle, pitch_angle, yaw_angle), (roll_bits, pitch_bits, yaw_bits), strict=True
        )
    ]
    drop = PRODUCT_FRAC - CORDIC_FRAC
    sin_drop = PRODUCT_FRAC - SIN_FRAC
    scaled_drop = SIN_FRAC + HALF_GAIN_FRAC - CORDIC_FRAC
    sum_width = SUM_WIDTH
    cordic_width = CORDIC.width
    last_accumulate = MULTIPLY_CYCLES + MULTIPLY_PIPELINE - 1
    p = MULTIPLY_PIPELINE
    multiply = exact_multiply(clk, rst, always_on, operand_a, operand_b, product)
    accumulators = [
        split_accumulator(clk, rst, clear_sums, add, subtract, product, total)
        for add, subtract, total in (
            (add_sin, subtract_sin, sum_sin),
            (add_roll_b, never, sum_roll_b),
            (never, subtract_roll_a, negated_roll_a),
            (never, subtract_yaw_a, negated_yaw_a),
            (add_yaw_b, never, sum_yaw_b),
        )
    ]

    @always_comb
    def accumulate():
        # Product k was issued at step k and is summed at step k + MULTIPLY_PIPELINE (p).
        summing = state == state_t.PRODUCTS
        clear_sums.next = state == state_t.CONVERT and waited == converted
        add_sin.next = summing and step == p
        subtract_sin.next = summing and step == p + 1
        add_roll_b.next = summing and (step == p + 2 or step == p + 3)
        subtract_roll_a.next = summing and (step == p + 4 or step == p + 5)
        subtract_yaw_a.next = summing and (step == p + 5 or step == p + 6)
        add_yaw_b.next = summing and (step == p + 7 or step == p + 8)

    @always_comb
    def operand_indices():
        first.next = FIRST_OPERANDS[step]
        second.next = SECOND_OPERANDS[step]

    @always_comb
    def flags():
        out_of_range.next = over_x or over_y or over_z or over_w or nan_x or nan_y or nan_z or nan_w

    @always_seq(clk.posedge, reset=rst)
    def round_sums():
        # 1 - 2·sum, 2·sum and 2·(wy - zx), rounded half up from the exact sums, registered
        # twice (rounded, then offset by the unit): the CORDICs start from registers
        value = intbv(0, min=-(1 << sum_width), max=1 << sum_width)
        unit = intbv(0, min=-(1 << (cordic_width - 1)), max=1 << (cordic_width - 1))
        unit[CORDIC_FRAC] = 1
        value[:] = negated_roll_a
        a_rounded.next = ((value >> (drop - 2)) + 1) >> 1
        value[:] = sum_roll_b
        b_roll.next = ((value >> (drop - 2)) + 1) >> 1
        value[:] = negated_yaw_a
        b_rounded.next = ((value >> (drop - 2)) + 1) >> 1
        value[:] = sum_yaw_b
        b_y.next = ((value >> (drop - 2)) + 1) >> 1
        pitch_y.next = ((scaled_sin >> (scaled_drop - 1)) + 1) >> 1
        a_roll.next = unit + a_rounded
        b_x.next = unit + b_rounded

    @always_comb
    def cordic_inputs():
        value = intbv(0, min=-(1 << sum_width), max=1 << sum_width)
        value[:] = sum_sin
        sin_pitch.next = ((value >> (sin_drop - 2)) + 1) >> 1
        if state == state_t.PITCH_START or state == state_t.PITCH_BUSY:
            a_x.next = lengths >> 2
            a_y.next = pitch_y
        else:
            a_x.next = a_roll
            a_y.next = b_roll
        a_in_valid.next = state == state_t.ROLL_YAW_START or state == state_t.PITCH_START
        b_in_valid.next = state == state_t.ROLL_YAW_START
        a_out_ready.next = (state == state_t.ROLL_YAW_BUSY and b_out_valid) or (
            state == state_t.PITCH_BUSY
        )
        b_out_ready.next = state == state_t.ROLL_YAW_BUSY and a_out_valid

    @always_seq(clk.posedge, reset=rst)
    def operands_in():
        if state == state_t.PRODUCTS:
            operand_a.next = selected_a
            operand_b.next = selected_b

    @always_seq(clk.posedge, reset=rst)
    def control():
        if state == state_t.IDLE:
            if in_valid:
                waited.next = 0
                state.next = state_t.CONVERT
        elif state == state_t.CONVERT:
            waited.next = waited + 1
            if waited == converted:
                qx.next = cx
                qy.next = cy
                qz.next = cz
                qw.next = cw
                bad_input.next = out_of_range
                step.next = 0
                state.next = state_t.PRODUCTS
        elif state == state_t.PRODUCTS:
            # The sums are `accumulate`'s; the last product, sin(pitch)·gain/2, is kept whole.
            if step == last_accumulate:
                scaled_sin.next = product
                state.next = state_t.ROUND
            step.next = step + 1
        elif state == state_t.ROUND:
            state.next = state_t.ROLL_YAW_START
        elif state == state_t.ROLL_YAW_START:
            if a_in_ready and b_in_ready:
                state.next = state_t.ROLL_YAW_BUSY
        elif state == state_t.ROLL_YAW_BUSY:
            if a_out_valid and b_out_valid:
                roll_angle.next = a_angle
                yaw_angle.next = b_angle
                lengths.next = a_magnitude + b_magnitude
                state.next = state_t.PITCH_START
        elif state == state_t.PITCH_START:
            if a_in_ready:
                state.next = state_t.PITCH_BUSY
        elif state == state_t.PITCH_BUSY:
            if a_out_valid:
                pitch_angle.next = a_angle
                waited.next = 0
                state.next = state_t.TO_FLOAT
        elif state == state_t.TO_FLOAT:
            waited.next = waited + 1
            if waited == to_float_last:
                state.next = state_t.DONE
        elif out_ready:
            state.next = state_t.IDLE

    @always_comb
    def outputs():
        nan = intbv(0)[64:]
        nan[63:51] = 0xFFF
        in_ready.next = state == state_t.CONVERT and waited == converted
        out_valid.next = state == state_t.DONE
        if bad_input:
            roll.next = nan
            pitch.next = nan
            yaw.next = nan
        else:
            roll.next = roll_bits
            pitch.next = pitch_bits
            yaw.next = yaw_bits

    return (
        converters,
        cordic_a,
        cordic_b,
        to_float,
        selectors,
        operand_indices,
        flags,
        cordic_inputs,
        operands_in,
        multiply,
        accumulators,
        accumulate,
        round_sums,
        control,
        outputs,
    )


@block
def select_operand(index, x, y, z, w, sin_pitch, operand):
    """One multiplier operand: a component, sin(pitch) or the constant gain/2 (by `index`)."""
    gain_rom = (HALF_GAIN,)

    @always_comb
    def select():
        gain = intbv(0, min=COMPONENT.min_raw, max=COMPONENT.max_raw + 1)
        gain[:] = gain_rom[0]
        if index == X:
            operand.next = x
        elif index == Y:
            operand.next = y
        elif index == Z:
            operand.next = z
        elif index == W:
            operand.next = w
        elif index == SIN:
            operand.next = sin_pitch
        else:
            operand.next = gain

    return select
