"""MyHDL vectoring CORDIC blocks: iterative (a rotation in two cycles) or pipelined (a stage each).

Both have the same ports and the bits of `rfc.lib.cordic.model.vectoring`. The iterative block
takes one input at a time: a micro-rotation registers the shifted operands on one cycle and adds
them on the next, so that no path runs through a barrel shifter and a wide adder at once
(`CordicConfig.iterative_latency` cycles from the input handshake to `out_valid`, initiation
interval `CordicConfig.iterative_interval`; an adder each for x, y and z, two barrel shifters
and three registers of area). The pipelined one takes an input every cycle (one stage of three
adders per iteration, the stages of `rfc.lib.cordic.stage`; latency
`CordicConfig.pipelined_latency`); `cordic_pipeline` is its datapath alone, for larger
pipelines. Outputs stay put while `out_valid` is high and `out_ready` low.

Wide constants reach VHDL only as ROM contents: MyHDL writes integers in expressions as VHDL
integers, which stop at 32 bits.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.arith.pipeline import signed_signal, stall_control
from rfc.lib.cordic.config import CordicConfig
from rfc.lib.cordic.stage import add_or_subtract, micro_rotation
from rfc.lib.types import Instances, SignalLike


# Shaped like `rfc.lib.arith.sincos_hdl.sincos` (a handshake block picking its variant).
@block
def cordic_vectoring(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    x: SignalLike,
    y: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    angle: SignalLike,
    magnitude: SignalLike,
    config: CordicConfig,
    pipelined: bool = False,
) -> Instances:
    """Vectoring CORDIC: atan2(y, x) and gain·sqrt(x² + y²), with valid/ready handshakes.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`.

    Args:
        x: Input, signed ``config.width`` bits.
        y: Input, signed ``config.width`` bits, same scale as `x`.
        angle: Output, signed ``config.angle_width`` bits: radians with ``config.angle_frac``
            fraction bits, in [-π, π] up to the residual (2**(1 - iterations)); exact when y
            is 0 (0 for (0, 0)).
        magnitude: Output, unsigned ``config.magnitude_width`` bits: gain·|(x, y)| in the
            scale of the inputs, rounded down.
        config: Widths and iterations.
        pipelined: One stage per iteration (a new input every cycle) instead of one
            iteration per cycle in a single stage.
    """
    variant = cordic_pipelined if pipelined else cordic_iterative
    return variant(
        clk, rst, in_valid, in_ready, x, y, out_valid, out_ready, angle, magnitude, config
    )


# Its micro-rotation is spelled out around `stage.add_or_subtract` rather than `stage.rotation`
# or `stage.looped_rotation`: the shifted operands and the turn are registered a cycle before
# the add, and a level vector's angle is held.
@block
def cordic_iterative(clk: SignalLike, rst: SignalLike, in_valid: SignalLike,
                     in_ready: SignalLike, x: SignalLike, y: SignalLike, out_valid: SignalLike,
                     out_ready: SignalLike, angle: SignalLike, magnitude: SignalLike,
                     config: CordicConfig) -> Instances:  # fmt: skip
    """A micro-rotation every two cycles through variable shifts; ports as `cordic_vectoring`.

    On the first cycle of a step the shifted operands ``x >> i``, ``y >> i`` and the turn
    ``±atan(2**-i)`` are registered, the one subtracted complemented and the turn's sign
    picked, by the sign of y; on the second each of x, y and z is one adder (the carry in of a
    subtraction as a low bit below both operands): one carry chain a sum, not a sum and a
    difference and a multiplexer. y changes only on the second cycle, so its sign is the
    same on both.
    """
    iterations = config.iterations
    internal = config.internal_width
    guard = config.guard
    y_top = internal - 1
    # The step counter rests at `iterations` while idle; that address reads 0.
    rom = (*config.atan_table, 0)
    negated_rom = tuple(-turn for turn in rom)
    xs = signed_signal(internal)
    ys = signed_signal(internal)
    zs = signed_signal(config.angle_width)
    x_shifted, y_shifted = signed_signal(internal), signed_signal(internal)
    turn = signed_signal(config.angle_width)
    step = Signal(intbv(iterations, min=0, max=iterations + 1))
    adding = Signal(bool(0))
    full = Signal(bool(0))
    level = Signal(bool(0))
    x_turned, y_turned = signed_signal(internal), signed_signal(internal)
    start_angle = signed_signal(config.angle_width)
    y_zero = Signal(bool(0))
    prerotate = cordic_prerotation(x, y, x_turned, y_turned, start_angle, y_zero, config)
    down = Signal(bool(0))
    x_sum, y_sum = signed_signal(internal), signed_signal(internal)
    add = add_or_subtract(down, xs, ys, y_shifted, x_shifted, x_sum, y_sum)

    @always_comb
    def direction() -> None:
        down.next = ys[y_top] == 0

    @always_seq(clk.posedge, reset=rst)
    def iterate() -> None:
        if step != iterations:
            if not adding:
                if down:
                    x_shifted.next = ~(xs >> step)
                    y_shifted.next = ys >> step
                    turn.next = rom[step]
                else:
                    x_shifted.next = xs >> step
                    y_shifted.next = ~(ys >> step)
                    turn.next = negated_rom[step]
                adding.next = True
            else:
                xs.next = x_sum
                ys.next = y_sum
                if not level:
                    zs.next = zs + turn
                if step == iterations - 1:
                    full.next = True
                step.next = step + 1
                adding.next = False
        elif full:
            if out_ready:
                full.next = False
        elif in_valid:
            xs.next = x_turned
            ys.next = y_turned
            zs.next = start_angle
            level.next = y_zero
            step.next = 0

    @always_comb
    def outputs() -> None:
        in_ready.next = step == iterations and not full
        out_valid.next = full
        magnitude.next = xs >> guard
        angle.next = zs

    return prerotate, add, direction, iterate, outputs


@block
def cordic_pipelined(clk: SignalLike, rst: SignalLike, in_valid: SignalLike,
                     in_ready: SignalLike, x: SignalLike, y: SignalLike, out_valid: SignalLike,
                     out_ready: SignalLike, angle: SignalLike, magnitude: SignalLike,
                     config: CordicConfig) -> Instances:  # fmt: skip
    """A stage per micro-rotation with fixed shifts; ports as `cordic_vectoring`."""
    advance = Signal(bool(0))
    valid_last = Signal(bool(0))
    datapath = cordic_pipeline(
        clk, rst, advance, in_valid, x, y, valid_last, angle, magnitude, config
    )

    control = stall_control(valid_last, out_ready, advance, in_ready, out_valid)

    return datapath, control


# Its stage list is also `rfc.lib.arith.sincos_hdl.sincos_pipelined`'s, in vectoring mode: a
# block holding both would rename every stage in the generated VHDL.
@block
def cordic_pipeline(clk: SignalLike, rst: SignalLike, advance: SignalLike, valid_in: SignalLike,
                    x: SignalLike, y: SignalLike, valid_out: SignalLike, angle: SignalLike,
                    magnitude: SignalLike, config: CordicConfig) -> Instances:  # fmt: skip
    """The unrolled vectoring CORDIC without handshakes: it moves when `advance` is high.

    A pair entering on a cycle with `advance` high comes out ``config.pipelined_latency`` advancing
    cycles later, `valid_out` marking the cycles that carry a result; ports otherwise as
    `cordic_vectoring`. For composing into a larger pipeline with one stall enable.
    """
    internal = config.internal_width
    guard = config.guard
    # Stage i holds the vector after i micro-rotations; stage 0 is the pre-rotated input. The
    # tag is (half turn, level): a level vector's angle is exactly its pre-rotation.
    count = config.iterations + 1
    xs = [signed_signal(internal) for _ in range(count)]
    ys = [signed_signal(internal) for _ in range(count)]
    zs = [signed_signal(config.angle_width) for _ in range(count)]
    valid = [Signal(bool(0)) for _ in range(count)]
    tags = [Signal(intbv(0)[2:]) for _ in range(count)]
    x_first, y_first, z_first, valid_first, tag_first = xs[0], ys[0], zs[0], valid[0], tags[0]
    last = count - 1
    x_last, z_last, valid_last, tag_last = xs[last], zs[last], valid[last], tags[last]
    x_turned, y_turned = signed_signal(internal), signed_signal(internal)
    start_angle = signed_signal(config.angle_width)
    y_zero = Signal(bool(0))
    turn = cordic_prerotation(x, y, x_turned, y_turned, start_angle, y_zero, config)
    pi_rom = (config.pi,)
    angle_bits = config.angle_width

    # Registers of one stage, like `stage.micro_rotation`'s; this one turns the input by π.
    @always_seq(clk.posedge, reset=rst)
    def prerotate() -> None:
        if advance:
            x_first.next = x_turned
            y_first.next = y_turned
            z_first.next = start_angle
            if x < 0:
                tag_first.next = 3 if y_zero else 2
            else:
                tag_first.next = 1 if y_zero else 0
            valid_first.next = valid_in

    stages = [
        micro_rotation(
            clk,
            rst,
            advance,
            i,
            angle_step,
            True,
            (valid[i], tags[i], xs[i], ys[i], zs[i]),
            (valid[i + 1], tags[i + 1], xs[i + 1], ys[i + 1], zs[i + 1]),
        )
        for i, angle_step in enumerate(config.atan_table)
    ]

    @always_comb
    def outputs() -> None:
        half_turn = intbv(0, min=-(1 << (angle_bits - 1)), max=1 << (angle_bits - 1))
        half_turn[:] = pi_rom[0]
        valid_out.next = valid_last
        magnitude.next = x_last >> guard
        if not tag_last[0]:
            angle.next = z_last
        elif tag_last[1]:
            angle.next = half_turn
        else:
            angle.next = 0

    return turn, prerotate, stages, outputs


@block
def cordic_prerotation(x: SignalLike, y: SignalLike, x_turned: SignalLike, y_turned: SignalLike,
                       start_angle: SignalLike, y_zero: SignalLike,
                       config: CordicConfig) -> Instances:  # fmt: skip
    """Inputs as the iterations start from them (combinational).

    Negative x is turned by π (both negated; the angle starts at +π when y >= 0, else -π) so
    that the micro-rotations only cover [-π/2, π/2]; x and y gain the guard bits; `y_zero`
    marks level inputs, whose angle is exact.
    """
    internal = config.internal_width
    guard = config.guard
    angle_bits = config.angle_width
    pi_rom = (config.pi,)

    @always_comb
    def turn() -> None:
        xi = intbv(0, min=-(1 << (internal - 1)), max=1 << (internal - 1))
        yi = intbv(0, min=-(1 << (internal - 1)), max=1 << (internal - 1))
        half_turn = intbv(0, min=-(1 << (angle_bits - 1)), max=1 << (angle_bits - 1))
        half_turn[:] = pi_rom[0]
        xi[:] = x
        yi[:] = y
        if x < 0:
            xi[:] = -xi
            yi[:] = -yi
            if y >= 0:
                start_angle.next = half_turn
            else:
                start_angle.next = -half_turn
        else:
            start_angle.next = 0
        x_turned.next = xi << guard
        y_turned.next = yi << guard
        y_zero.next = y == 0

    return turn
