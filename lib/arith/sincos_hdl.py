"""MyHDL sine/cosine CORDIC blocks, iterative (one rotation per cycle) or pipelined (II = 1).

Both have the same ports and the bits of `rfc.lib.arith.sincos.sincos`; from the input
handshake to `out_valid` the pipelined block takes `SinCosConfig.latency` cycles and the
iterative one `SinCosConfig.iterative_latency` (a cycle more: its angle reduction is
registered halfway). The iterative block takes one input at a time (initiation interval
`iterative_latency` + 2: three adders, two barrel shifters, the turn read from its ROM a cycle
ahead);
the pipelined one takes an input every cycle (three adders per iteration, the stages of
`rfc.lib.cordic.stage`). Outputs stay put while `out_valid` is high and `out_ready` low. Wide
constants reach VHDL as ROM contents (VHDL integers stop at 32 bits).
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.arith.pipeline import signed_signal, stall_control
from rfc.lib.arith.sincos import SinCosConfig
from rfc.lib.cordic.stage import looped_rotation, micro_rotation
from rfc.lib.types import Instances, SignalLike


@block
def sincos(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    angle: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    cos: SignalLike,
    sin: SignalLike,
    config: SinCosConfig,
    pipelined: bool = False,
) -> Instances:
    """Cosine and sine of a fixed-point angle, with valid/ready handshakes.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`.

    Args:
        angle: Input, signed raw integer of ``config.angle_format`` (radians in [-8, 8)).
        cos: Output, signed raw integer of ``config.out_format``.
        sin: Output, signed raw integer of ``config.out_format``.
        config: Precision and iterations.
        pipelined: One stage per iteration (a new angle every cycle) instead of one
            iteration per cycle in a single stage.
    """
    variant = sincos_pipelined if pipelined else sincos_iterative
    return variant(clk, rst, in_valid, in_ready, angle, out_valid, out_ready, cos, sin, config)


# Ports as `sincos`'s, spelled again: each variant is a block of its own that rfc check's
# timing table knows by its function (rfc.lib.arith.timing).
@block
def sincos_iterative(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    angle: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    cos: SignalLike,
    sin: SignalLike,
    config: SinCosConfig,
) -> Instances:
    """One micro-rotation per cycle through variable shifts; ports as `sincos`.

    The turn atan(2**-i) is read from its ROM a cycle ahead into a register, so that a cycle's
    path is the shift and one add (`looped_rotation`), not the ROM read and an add. The angle's
    reduction takes two cycles, a register between its two halves (`wrap_half_turns`, then
    `fold_quarter_turns`): both in one cycle behind the caller's register made the longest
    path (5.62 ns of cells in Franka's engine).
    """
    steps = config.steps
    # The turn after the last step is read as 0 (never used).
    rom = (*config.atan_table, 0)
    start_rom = (config.start,)
    first_turn_rom = (config.atan_table[0],)
    turn = signed_signal(config.z_width)
    following = Signal(intbv(1, min=0, max=steps + 2))
    xs, ys = signed_signal(config.xy_width), signed_signal(config.xy_width)
    zs = signed_signal(config.z_width)
    flip = Signal(bool(0))
    step = Signal(intbv(steps, min=0, max=steps + 1))
    full = Signal(bool(0))
    z_start, flip_start = signed_signal(config.z_width), Signal(bool(0))
    wrapped, wrapped_held = signed_signal(config.z_width + 2), signed_signal(config.z_width + 2)
    reducing = Signal(bool(0))
    wrap = wrap_half_turns(angle, wrapped, config)
    fold = fold_quarter_turns(wrapped_held, z_start, flip_start, config)
    round_cos = sincos_rounding(xs, flip, cos, config)
    round_sin = sincos_rounding(ys, flip, sin, config)
    x_next, y_next, z_next = Signal(xs.val), Signal(ys.val), Signal(zs.val)
    rotate = looped_rotation(False, step, turn, (xs, ys, zs), (x_next, y_next, z_next))

    @always_comb
    def count() -> None:
        following.next = step + 1

    @always_seq(clk.posedge, reset=rst)
    def iterate() -> None:
        if step != steps:
            xs.next = x_next
            ys.next = y_next
            zs.next = z_next
            turn.next = rom[following]
            if step == steps - 1:
                full.next = True
            step.next = following
        elif full:
            if out_ready:
                full.next = False
        elif reducing:
            xs.next = start_rom[0]
            ys.next = 0
            zs.next = z_start
            turn.next = first_turn_rom[0]
            flip.next = flip_start
            step.next = 0
            reducing.next = False
        elif in_valid:
            wrapped_held.next = wrapped
            reducing.next = True

    @always_comb
    def outputs() -> None:
        in_ready.next = step == steps and not full and not reducing
        out_valid.next = full

    return wrap, fold, round_cos, round_sin, rotate, count, iterate, outputs


# Ports as `sincos`'s (see `sincos_iterative`).
@block
def sincos_pipelined(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    angle: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    cos: SignalLike,
    sin: SignalLike,
    config: SinCosConfig,
) -> Instances:
    """A stage per micro-rotation with fixed shifts; ports as `sincos`."""
    count = config.steps + 1
    # Stage i holds the vector after i micro-rotations; stage 0 is the reduced input.
    xs = [signed_signal(config.xy_width) for _ in range(count)]
    ys = [signed_signal(config.xy_width) for _ in range(count)]
    zs = [signed_signal(config.z_width) for _ in range(count)]
    valid = [Signal(bool(0)) for _ in range(count)]
    flips = [Signal(bool(0)) for _ in range(count)]
    x_first, y_first, z_first, valid_first, flip_first = xs[0], ys[0], zs[0], valid[0], flips[0]
    last = count - 1
    valid_last = valid[last]
    advance = Signal(bool(0))
    start_rom = (config.start,)
    z_start, flip_start = signed_signal(config.z_width), Signal(bool(0))
    ends = sincos_ends(
        angle, z_start, flip_start, xs[last], ys[last], flips[last], cos, sin, config
    )

    @always_seq(clk.posedge, reset=rst)
    def load() -> None:
        if advance:
            x_first.next = start_rom[0]
            y_first.next = 0
            z_first.next = z_start
            flip_first.next = flip_start
            valid_first.next = in_valid

    # The same stages as `rfc.lib.cordic.hdl.cordic_pipeline`'s, in rotation mode: a block
    # holding them both would rename every stage of the generated VHDL (MyHDL names instances
    # by their blocks).
    stages = [
        micro_rotation(
            clk,
            rst,
            advance,
            i,
            step,
            False,
            (valid[i], flips[i], xs[i], ys[i], zs[i]),
            (valid[i + 1], flips[i + 1], xs[i + 1], ys[i + 1], zs[i + 1]),
        )
        for i, step in enumerate(config.atan_table)
    ]

    control = stall_control(valid_last, out_ready, advance, in_ready, out_valid)
    return ends, load, stages, control


@block
def sincos_ends(
    angle: SignalLike,
    z_start: SignalLike,
    flip_start: SignalLike,
    x: SignalLike,
    y: SignalLike,
    flip: SignalLike,
    cos: SignalLike,
    sin: SignalLike,
    config: SinCosConfig,
) -> Instances:
    """The pipelined variant's ends: the angle reduced, `cos` and `sin` rounded.

    The iterative variant registers its reduction halfway and builds its own ends.
    """
    reduce = sincos_reduction(angle, z_start, flip_start, config)
    round_cos = sincos_rounding(x, flip, cos, config)
    round_sin = sincos_rounding(y, flip, sin, config)
    return reduce, round_cos, round_sin


@block
def sincos_reduction(
    angle: SignalLike, z_start: SignalLike, flip_start: SignalLike, config: SinCosConfig
) -> Instances:
    """The angle reduced to [-π/2, π/2] with the guard bits, and whether to negate (comb)."""
    wrapped = signed_signal(config.z_width + 2)
    wrap = wrap_half_turns(angle, wrapped, config)
    fold = fold_quarter_turns(wrapped, z_start, flip_start, config)
    return wrap, fold


@block
def wrap_half_turns(angle: SignalLike, wrapped: SignalLike, config: SinCosConfig) -> Instances:
    """The angle with its guard bits, brought into [-π, π] by a turn of 2π (comb)."""
    wide = config.z_width + 2
    pi_rom, two_pi_rom = (config.pi,), (config.two_pi,)
    guard = config.guard

    @always_comb
    def wrap() -> None:
        pi = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        two_pi = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        z = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        pi[:] = pi_rom[0]
        two_pi[:] = two_pi_rom[0]
        z[:] = angle
        z[:] = z << guard
        if z > pi:
            z[:] = z - two_pi
        elif z < -pi:
            z[:] = z + two_pi
        wrapped.next = z

    return wrap


@block
def fold_quarter_turns(
    wrapped: SignalLike, z_start: SignalLike, flip_start: SignalLike, config: SinCosConfig
) -> Instances:
    """An angle in [-π, π] folded into [-π/2, π/2] by π, and whether that negates (comb)."""
    wide = config.z_width + 2
    pi_rom, half_rom = (config.pi,), (config.half_pi,)

    @always_comb
    def fold() -> None:
        pi = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        half = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        z = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        pi[:] = pi_rom[0]
        half[:] = half_rom[0]
        z[:] = wrapped
        flip_start.next = False
        if z > half:
            z[:] = z - pi
            flip_start.next = True
        elif z < -half:
            z[:] = z + pi
            flip_start.next = True
        z_start.next = z

    return fold


@block
def sincos_rounding(
    value: SignalLike, flip: SignalLike, result: SignalLike, config: SinCosConfig
) -> Instances:
    """A register's value, negated when `flip`, rounded half up from the guard bits (comb)."""
    wide = config.xy_width + 1
    guard = config.guard
    half = 1 << (guard - 1)

    @always_comb
    def round_half_up() -> None:
        v = intbv(0, min=-(1 << (wide - 1)), max=1 << (wide - 1))
        if flip:
            v[:] = -value
        else:
            v[:] = value
        v[:] = v + half
        result.next = v >> guard

    return round_half_up
