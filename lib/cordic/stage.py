"""The CORDIC micro-rotation, written once for every CORDIC of rfc.lib.

Rotation mode (sine/cosine) turns towards the residual angle `z`; vectoring mode (atan2 and
magnitude) turns towards y = 0. Either way a micro-rotation turns (x, y) by ±atan(2**-i) with
shifts by i and adds the opposite turn to `z`. `rotation` is that step alone (combinational),
which the iterative blocks loop through with a variable shift; `micro_rotation` is one
registered stage of an unrolled pipeline, which also passes a valid bit and a tag (what later
stages need to know about the input: a negation, a level vector) along unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.types import Instances, SignalLike


@block
def rotation(vectoring: bool, shift: int | SignalLike, turns: tuple[int, ...],
             index: int | SignalLike, before: Sequence[SignalLike],
             after: Sequence[SignalLike]) -> Instances:  # fmt: skip
    """``(x, y, z)`` after one micro-rotation (combinational).

    Args:
        vectoring: Turn towards y = 0 (vectoring mode) instead of towards z = 0 (rotation).
        shift: The micro-rotation's index i, an int (a pipeline stage) or a Signal (a loop).
        turns: ``atan(2**-i)`` as raw integers of `z`'s format, a ROM read at `index` (wide
            constants reach VHDL only as ROM contents).
        index: Where the turn is in `turns`, an int or a Signal.
        before: ``(x, y, z)`` signals.
        after: ``(x, y, z)`` signals of the same widths.
    """
    x, y, z = before
    x_next, y_next, z_next = after
    width = len(z)
    # Turn "down" (x grows by y's share, y shrinks by x's, z grows by the turn) when the sign
    # bit of `lead` is `down_sign`: y >= 0 in vectoring mode, z < 0 in rotation mode.
    lead = y if vectoring else z
    top = len(lead) - 1
    down_sign = 0 if vectoring else 1

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

    Args:
        clk: Clock.
        rst: Synchronous reset (a MyHDL ``ResetSignal``).
        advance: Input, the pipeline moves on this cycle.
        shift: The stage's index i: the turn is ±atan(2**-i).
        angle_step: ``atan(2**-shift)`` as a raw integer of `z`'s format.
        vectoring: Turn towards y = 0 (vectoring mode) instead of towards z = 0 (rotation).
        before: ``(valid, tag, x, y, z)`` signals into the stage.
        after: ``(valid, tag, x, y, z)`` registers out of it, of the same widths.
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
