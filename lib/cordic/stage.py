"""The CORDIC micro-rotation, written once for every CORDIC of rfc.lib.

Rotation mode (sine/cosine) turns towards the residual angle `z`; vectoring mode (atan2 and
magnitude) turns towards y = 0. Either way a micro-rotation turns (x, y) by ±atan(2**-i) with
shifts by i and adds the opposite turn to `z`. `rotation` is that step alone (combinational)
and `micro_rotation` one registered stage of an unrolled pipeline built on it, which also
passes a valid bit and a tag (what later stages need to know about the input: a negation, a
level vector) along unchanged. `looped_rotation` is the same step for a loop that runs one
micro-rotation per cycle (the sine/cosine's), built for the variable shift's timing: it adds
x and y with one carry chain apiece (`add_or_subtract`, which the iterative vectoring CORDIC of
`rfc.lib.cordic.hdl` instantiates too).

Arguments the three share: `vectoring` turns towards y = 0 (vectoring mode) instead of towards
z = 0 (rotation mode); `before` and `after` are the vector's signals into and out of the step
(``(x, y, z)``, and in a stage ``(valid, tag, x, y, z)``), of the same widths.
"""

from __future__ import annotations

from collections.abc import Sequence

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.types import Instances, SignalLike


def _turn_down(vectoring: bool, y: SignalLike, z: SignalLike) -> tuple[SignalLike, int, int]:
    """When a micro-rotation turns "down": the sign bit (signal, index) and its value.

    Down, x grows by y's share, y shrinks by x's and z grows by the turn: when y >= 0 in
    vectoring mode, when z < 0 in rotation mode.
    """
    lead = y if vectoring else z
    return lead, len(lead) - 1, 0 if vectoring else 1


@block
def rotation(vectoring: bool, shift: int | SignalLike, turns: tuple[int, ...],
             index: int | SignalLike, before: Sequence[SignalLike],
             after: Sequence[SignalLike]) -> Instances:  # fmt: skip
    """``(x, y, z)`` after one micro-rotation (combinational).

    `vectoring`, `before` and `after` as the module describes.

    Args:
        shift: The micro-rotation's index i, an int (a pipeline stage) or a Signal (a loop).
        turns: ``atan(2**-i)`` as raw integers of `z`'s format, a ROM read at `index` (wide
            constants reach VHDL only as ROM contents).
        index: Where the turn is in `turns`, an int or a Signal.
    """
    x, y, z = before
    x_next, y_next, z_next = after
    width = len(z)
    lead, top, down_sign = _turn_down(vectoring, y, z)

    @always_comb
    def turn_vector() -> None:
        turn = intbv(0, min=-(1 << (width - 1)), max=1 << (width - 1))
        turn[:] = turns[index]
        if lead[top] == down_sign:
            x_next.next = x + (y >> shift)
            y_next.next = y - (x >> shift)
            z_next.next = z + turn
        else:
            x_next.next = x - (y >> shift)
            y_next.next = y + (x >> shift)
            z_next.next = z - turn

    return turn_vector


@block
def micro_rotation(clk: SignalLike, rst: SignalLike, advance: SignalLike, shift: int,
                   angle_step: int, vectoring: bool, before: Sequence[SignalLike],
                   after: Sequence[SignalLike]) -> Instances:  # fmt: skip
    """One micro-rotation as a pipeline stage, registered on the cycles `advance` is high.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`; `vectoring`, `before`
    and `after` as the module describes.

    Args:
        shift: The stage's index i: the turn is ±atan(2**-i).
        angle_step: ``atan(2**-shift)`` as a raw integer of `z`'s format.
    """
    valid_in, tag_in, x_in, y_in, z_in = before
    x_next, y_next, z_next = Signal(x_in.val), Signal(y_in.val), Signal(z_in.val)
    step = rotation(
        vectoring, shift, (angle_step,), 0, (x_in, y_in, z_in), (x_next, y_next, z_next)
    )

    valid_out, tag_out, x_out, y_out, z_out = after

    # One process for the stage's registers (a process per register would triple the
    # generators MyHDL converts in a long pipeline).
    @always_seq(clk.posedge, reset=rst)
    def hold() -> None:
        if advance:
            valid_out.next = valid_in
            tag_out.next = tag_in
            x_out.next = x_next
            y_out.next = y_next
            z_out.next = z_next

    return step, hold


@block
def add_or_subtract(
    down: SignalLike,
    x: SignalLike,
    y: SignalLike,
    to_x: SignalLike,
    to_y: SignalLike,
    x_next: SignalLike,
    y_next: SignalLike,
) -> Instances:
    """``x + to_x`` and ``y + to_y`` of a micro-rotation, one carry chain each (combinational).

    The caller gives the operand a side subtracts complemented (`to_y` when turning `down`,
    `to_x` when not): ``y - a`` is ``y + ~a + 1``, and that 1 is the carry in, a low bit below
    both operands. A sum and a difference picked by the sign were two chains and a multiplexer.
    `to_x` and `to_y` are `x`'s width; `x_next` and `y_next` are signed.
    """
    width = len(x)

    @always_comb
    def add() -> None:
        left = intbv(0)[width + 1 :]
        right = intbv(0)[width + 1 :]
        total = intbv(0)[width + 2 :]
        left[width + 1 : 1] = x[width:]
        left[0] = 1
        right[width + 1 : 1] = to_x[width:]
        right[0] = not down
        total[:] = left + right
        x_next.next = total[width + 1 : 1].signed()
        left[width + 1 : 1] = y[width:]
        right[width + 1 : 1] = to_y[width:]
        right[0] = down
        total[:] = left + right
        y_next.next = total[width + 1 : 1].signed()

    return add


# One idea with `rotation`, two builds. A fixed shift is wires, so a pipeline stage keeps the
# plain sum-or-difference: with one carry chain a sum (`add_or_subtract`'s form), the
# pipelined quaternion core's 114 stages mapped to 4 % fewer LUTs and 3.17 instead of 3.65 ns,
# but MyHDL's longer process in each stage made its cold `rfc build` 16-19 s instead of
# 11-13 s. A loop's variable shift needs every other level of logic removed.
@block
def looped_rotation(
    vectoring: bool,
    shift: SignalLike,
    turn: SignalLike,
    before: Sequence[SignalLike],
    after: Sequence[SignalLike],
) -> Instances:
    """``(x, y, z)`` after micro-rotation `shift` of an iterative loop (combinational).

    The same turn as `rotation` with a variable shift, built for one iteration per cycle at
    100 MHz: the turn atan(2**-i) comes from a register (the loop reads its ROM a cycle ahead),
    the shift is unsigned with the sign filled in (a signed shift amount made Yosys negate it
    first), and each of x and y is one adder that adds the shifted operand or its complement
    plus 1, so that its path is a barrel shifter and one carry chain.

    `vectoring`, `before` and `after` as the module describes.

    Args:
        shift: The micro-rotation's index i (a Signal).
        turn: ``atan(2**-i)`` as a raw integer of `z`'s format (a register).
    """
    x, y, z = before
    x_next, y_next, z_next = after
    width = len(x)
    lead, top, down_sign = _turn_down(vectoring, y, z)

    down = Signal(bool(0))
    to_x, to_y = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
    add = add_or_subtract(down, x, y, to_x, to_y, x_next, y_next)

    @always_comb
    def turn_vector() -> None:
        fill = intbv(0)[width:]  # the bits an arithmetic shift fills with the sign
        fill[:] = ~fill
        fill[:] = fill >> shift
        fill[:] = ~fill
        x_shifted = intbv(0)[width:]
        x_shifted[:] = x[width:]
        x_shifted[:] = x_shifted >> shift
        if x[width - 1]:
            x_shifted[:] = x_shifted | fill
        y_shifted = intbv(0)[width:]
        y_shifted[:] = y[width:]
        y_shifted[:] = y_shifted >> shift
        if y[width - 1]:
            y_shifted[:] = y_shifted | fill
        # x_shifted becomes y's addend and y_shifted x's: complemented where subtracted
        if lead[top] == down_sign:
            x_shifted[:] = ~x_shifted
            z_next.next = z + turn
        else:
            y_shifted[:] = ~y_shifted
            z_next.next = z - turn
        down.next = lead[top] == down_sign
        to_x.next = y_shifted
        to_y.next = x_shifted

    return add, turn_vector
