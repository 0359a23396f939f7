"""Quaternion → Euler angles, pipelined: a new quaternion every cycle (initiation interval 1).

The same integer steps as the iterative core (`quat_to_euler.reference` with `PIPELINED`), laid
out in space instead of time: four pipelined float64 → fixed converters, nine exact products at
once, the roll and yaw CORDICs side by side as unrolled pipelines, then the pitch CORDIC on their
lengths, and three pipelined fixed → float64 converters. No stage holds more than a carry chain
or a few LUT levels of logic, so that the core keeps within half a 100 MHz period of 7-series
cell delay (docs/performance.md). Every register moves on one stall enable, while the result
queue at the end has room: when the consumer does not take results, the queue fills, then the
whole pipeline holds and takes no new quaternion until a result leaves.

Stages (registers), from the input handshake: the float64 → Q2.44 (`PIPELINED`) converters'
(`rfc.lib.fixed.pipeline`, the first one takes the handshake); exact products (limb products on
the DSP48s' M and P registers, then their sums in a tree); the five sums; the CORDIC inputs,
cut to their scale, then rounded; roll and yaw CORDICs (prerotation and a stage per iteration);
lengths; pitch CORDIC; angles; the fixed → float64 converters'; the result queue (float64).
sin(pitch)·gain/2 and the roll and yaw angles wait in delay lines beside the CORDICs.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv
from quat_to_euler import PIPELINED

from rfc.lib.arith.mac_hdl import exact_multiply, exact_multiply_stages
from rfc.lib.arith.pipeline import data_delay, delay_line, result_queue
from rfc.lib.cordic.hdl import cordic_pipeline
from rfc.lib.fixed.pipeline import (
    FIXED_TO_FLOAT_STAGES,
    FLOAT_TO_FIXED_STAGES,
    fixed_to_float_pipeline,
    float_to_fixed_pipeline,
)

CORDIC = PIPELINED.cordic
#: Registers a CORDIC adds: the prerotation and one per iteration.
CORDIC_STAGES = CORDIC.iterations + 1
#: Registers of an exact product of two components (limb products, their sums).
PRODUCT_STAGES = exact_multiply_stages(PIPELINED.component.width, PIPELINED.component.width)
#: Cycles from the input handshake until `out_valid` is high when the consumer keeps up: the
#: float → fixed converters, the product, sum, scaled and rounded registers, two CORDICs, the
#: lengths,
#: the angles, the fixed → float converters and the result queue, less one (the handshake loads
#: the first).
LATENCY = FLOAT_TO_FIXED_STAGES + PRODUCT_STAGES + 3 + 2 * CORDIC_STAGES + 2
LATENCY += FIXED_TO_FLOAT_STAGES + 1 - 1
#: Results the queue holds while the consumer is slow (one entry of four stays free).
QUEUE_DEPTH = 4
#: A quaternion every cycle while the results are taken.
INITIATION_INTERVAL = 1


def _signed(bits: int) -> Signal:
    return Signal(intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1)))


@block
def quat_to_euler_pipelined(
    clk, rst, x, y, z, w, in_valid, in_ready, roll, pitch, yaw, out_valid, out_ready
):
    """Quaternion (x, y, z, w) → Euler angles (roll, pitch, yaw), float64 in and out.

    Ports, domain and NaN behaviour as `quat_to_euler.quat_to_euler`; latency `LATENCY` cycles,
    initiation interval 1. Results stay on the outputs until taken.
    """
    advance = Signal(bool(0))
    component = PIPELINED.component
    word = 64

    # Components: Q2.44 with the out-of-domain flags, converted as they arrive.
    overflows = [Signal(bool(0)) for _ in range(4)]
    invalids = [Signal(bool(0)) for _ in range(4)]
    qx, qy, qz, qw = (component.signal() for _ in range(4))
    valid_q, valid_cordic = Signal(bool(0)), Signal(bool(0))
    bad_q, bad_cordic, bad_rolled, bad_angles = (Signal(bool(0)) for _ in range(4))
    converters = [
        float_to_fixed_pipeline(clk, advance, bits, raw, over, nan, component)
        for bits, raw, over, nan in zip((x, y, z, w), (qx, qy, qz, qw), overflows, invalids,
                                        strict=True)
    ]  # fmt: skip
    valid_wait = delay_line(clk, rst, advance, in_valid, valid_q, FLOAT_TO_FIXED_STAGES)

    # The nine exact products and their five sums.
    product_width = 2 * component.width
    products = [_signed(product_width) for _ in range(9)]
    pxx, pyy, pzz, pwx, pyz, pwz, pxy, pwy, pzx = products
    pairs = ((qx, qx), (qy, qy), (qz, qz), (qw, qx), (qy, qz), (qw, qz), (qx, qy), (qw, qy),
             (qz, qx))  # fmt: skip
    multipliers = [
        exact_multiply(clk, rst, advance, a, b, product)
        for (a, b), product in zip(pairs, products, strict=True)
    ]
    sum_roll_a, sum_roll_b, sum_yaw_a, sum_yaw_b, sum_sin = (
        _signed(PIPELINED.sum_width) for _ in range(5)
    )
    # valid and out-of-domain flags beside the product, sum, scaled and rounded registers
    flags = [
        delay_line(clk, rst, advance, source, target, PRODUCT_STAGES + 3)
        for source, target in ((valid_q, valid_cordic), (bad_q, bad_cordic))
    ]

    # CORDIC inputs (Q6.40) and sin(pitch) (Q6.36), registered, rounded half up from the exact
    # sums.
    width = CORDIC.width
    a_x, a_y, b_x, b_y = (_signed(width) for _ in range(4))
    sin_pitch = component.signal()
    roll_valid, yaw_valid, pitch_valid = (Signal(bool(0)) for _ in range(3))
    roll_angle, yaw_angle, pitch_angle = (_signed(CORDIC.angle_width) for _ in range(3))
    roll_length, yaw_length, pitch_length = (
        Signal(intbv(0)[CORDIC.magnitude_width :]) for _ in range(3)
    )
    roll_cordic = cordic_pipeline(
        clk, rst, advance, valid_cordic, a_x, a_y, roll_valid, roll_angle, roll_length, CORDIC
    )
    yaw_cordic = cordic_pipeline(
        clk, rst, advance, valid_cordic, b_x, b_y, yaw_valid, yaw_angle, yaw_length, CORDIC
    )

    # sin(pitch)·gain/2, rounded to the CORDIC's scale, waits beside the roll/yaw CORDICs.
    scaled_product = _signed(2 * component.width)
    scaled_sin, scaled_sin_late = _signed(width), _signed(width)
    half_gain = component.signal()
    scale = exact_multiply(clk, rst, advance, sin_pitch, half_gain, scaled_product)
    sin_wait = data_delay(
        clk, advance, scaled_sin, scaled_sin_late, CORDIC_STAGES + 1 - PRODUCT_STAGES
    )
    bad_wait = delay_line(clk, rst, advance, bad_cordic, bad_rolled, CORDIC_STAGES)

    # Pitch = atan2(sin(pitch)·gain, mean length): the lengths registered, then the CORDIC.
    lengths = Signal(intbv(0)[CORDIC.magnitude_width + 1 :])
    roll_held, yaw_held = _signed(CORDIC.angle_width), _signed(CORDIC.angle_width)
    scaled_held = _signed(width)
    valid_lengths, bad_lengths = Signal(bool(0)), Signal(bool(0))
    p_x = _signed(width)
    pitch_cordic = cordic_pipeline(
        clk, rst, advance, valid_lengths, p_x, scaled_held, pitch_valid, pitch_angle,
        pitch_length, CORDIC,
    )  # fmt: skip
    roll_late, yaw_late = _signed(CORDIC.angle_width), _signed(CORDIC.angle_width)
    angle_waits = [
        data_delay(clk, advance, roll_held, roll_late, CORDIC_STAGES),
        data_delay(clk, advance, yaw_held, yaw_late, CORDIC_STAGES),
        delay_line(clk, rst, advance, bad_lengths, bad_angles, CORDIC_STAGES),
    ]

    # Angles registered, then float64.
    angle_format = PIPELINED.angle
    final = [angle_format.signal() for _ in range(3)]
    valid_final, bad_final, push = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    valid_float, bad_float = Signal(bool(0)), Signal(bool(0))
    floats = [Signal(intbv(0)[word:]) for _ in range(3)]
    to_float = [
        fixed_to_float_pipeline(clk, advance, a, f, angle_format)
        for a, f in zip(final, floats, strict=True)
    ]
    float_flags = [
        delay_line(clk, rst, advance, source, target, FIXED_TO_FLOAT_STAGES)
        for source, target in ((valid_final, valid_float), (bad_final, bad_float))
    ]
    results = [Signal(intbv(0)[word:]) for _ in range(3)]
    result, queued = ConcatSignal(*results), Signal(intbv(0)[3 * word :])
    queue = result_queue(clk, rst, push, result, advance, out_valid, out_ready, queued, QUEUE_DEPTH)

    drop = PIPELINED.product_frac - PIPELINED.cordic_frac
    sin_drop = PIPELINED.product_frac - PIPELINED.sin_frac
    scaled_drop = PIPELINED.sin_frac + PIPELINED.half_gain_frac - PIPELINED.cordic_frac
    sum_width = PIPELINED.sum_width
    cordic_frac = PIPELINED.cordic_frac
    gain_rom = (PIPELINED.half_gain,)
    cut_roll_a, cut_roll_b, cut_yaw_a, cut_yaw_b = (
        _signed(sum_width + 1 - (drop - 2)) for _ in range(4)
    )

    # The sums negated where needed and cut to the CORDIC's scale plus a rounding bit, then
    # rounded half up: two registers, so that the 93-bit negation and the rounding carry are
    # not one path.
    @always_seq(clk.posedge, reset=None)
    def scale_sums():
        if advance:
            value = intbv(0, min=-(1 << sum_width), max=1 << sum_width)
            value[:] = -sum_roll_a
            cut_roll_a.next = value >> (drop - 2)
            value[:] = sum_roll_b
            cut_roll_b.next = value >> (drop - 2)
            value[:] = -sum_yaw_a
            cut_yaw_a.next = value >> (drop - 2)
            value[:] = sum_yaw_b
            cut_yaw_b.next = value >> (drop - 2)

    @always_seq(clk.posedge, reset=None)
    def rounding():
        if advance:
            unit = intbv(0, min=-(1 << (width - 1)), max=1 << (width - 1))
            unit[cordic_frac] = 1
            a_x.next = unit + ((cut_roll_a + 1) >> 1)
            a_y.next = (cut_roll_b + 1) >> 1
            b_x.next = unit + ((cut_yaw_a + 1) >> 1)
            b_y.next = (cut_yaw_b + 1) >> 1

    @always_comb
    def scaling():
        half_gain.next = gain_rom[0]
        scaled_sin.next = ((scaled_product >> (scaled_drop - 1)) + 1) >> 1
        p_x.next = lengths >> 2

    @always_comb
    def results_out():
        nan = intbv(0)[64:]
        nan[63:51] = 0xFFF
        in_ready.next = advance
        push.next = advance and valid_float
        bad_q.next = (
            overflows[0] or overflows[1] or overflows[2] or overflows[3]
            or invalids[0] or invalids[1] or invalids[2] or invalids[3]
        )  # fmt: skip
        if bad_float:
            results[0].next = nan
            results[1].next = nan
            results[2].next = nan
        else:
            results[0].next = floats[0]
            results[1].next = floats[1]
            results[2].next = floats[2]
        roll.next = queued[3 * word : 2 * word]
        pitch.next = queued[2 * word : word]
        yaw.next = queued[word:]

    @always_seq(clk.posedge, reset=rst)
    def stages():
        if advance:
            sum_roll_a.next = pxx + pyy
            sum_roll_b.next = pwx + pyz
            sum_yaw_a.next = pyy + pzz
            sum_yaw_b.next = pwz + pxy
            sum_sin.next = pwy - pzx
            sin_pitch.next = ((sum_sin >> (sin_drop - 2)) + 1) >> 1
            roll_held.next = roll_angle
            yaw_held.next = yaw_angle
            scaled_held.next = scaled_sin_late
            lengths.next = roll_length + yaw_length
            valid_lengths.next = roll_valid
            bad_lengths.next = bad_rolled
            final[0].next = roll_late
            final[1].next = pitch_angle
            final[2].next = yaw_late
            valid_final.next = pitch_valid
            bad_final.next = bad_angles

    return (
        converters, valid_wait, multipliers, flags, roll_cordic, yaw_cordic, scale, sin_wait,
        bad_wait, pitch_cordic, angle_waits, to_float, float_flags, queue, scale_sums, rounding,
        scaling,
        results_out, stages,
    )  # fmt: skip
