"""The frame-length circuit (the paper's Algorithm 1): a frame's length from its field lengths.

A publisher must send the frame's length before its first byte. Everything static is folded at
compile time; at run time the circuit adds the lengths of the top-level strings and sequences
(scaled by their element sizes) and the CDR padding those lengths cause. Padding depends only
on positions modulo 8, so it is computed on 3-bit values along the frame (one `Stage` after
another) and added once: the wide adders only see the length inputs and the small padding
terms, which keeps the circuit small and purely combinational.

Only plans whose length follows from top-level lengths have such a circuit (`Plan.
store_and_forward` is false): strings, primitive sequences, and sequences of messages whose
element is one fixed-size record (so that every element has the same stride).
"""

from __future__ import annotations

from dataclasses import dataclass

from myhdl import Constant, Signal, always_comb, block, intbv

from rfc.lib.converters.ports import count_bits
from rfc.lib.converters.steps import Loop, Payload, Plan, Record
from rfc.lib.types import Instances, SignalLike


@dataclass(frozen=True)
class Stage:
    """One place along the frame where run-time lengths or padding enter.

    A stage without a port is a record of `fixed` bytes. A stage with a port counts items:
    ``count * scale + fixed`` bytes for a string or primitive sequence, ``(count - 1) * scale
    + fixed`` for a sequence of messages (`scale` is the stride, `fixed` one element), where
    `sequence` says which; an empty sequence adds nothing.

    Attributes:
        port: Length or count input, None for a record.
        maximum: Largest count the input carries.
        scale: Bytes per counted item (the stride of a sequence of messages).
        fixed: Constant bytes: a record's size, a CDR string's NUL, an element's size.
        align: Alignment (1, 2, 4 or 8) of the stage's first byte; a sequence is only aligned
            when it is not empty.
        sequence: Whether the stage is a sequence of messages.
    """

    port: str | None
    maximum: int
    scale: int
    fixed: int
    align: int
    sequence: bool = False

    @property
    def largest(self) -> int:
        """Most bytes the stage adds, padding included."""
        return self.align - 1 + self.maximum * self.scale + self.fixed


@dataclass(frozen=True)
class LengthFormula:
    """Frame length = `static` + the stages, in frame order.

    Attributes:
        static: Bytes of the first record (header included): everything before the first
            string or sequence.
        start_gap: Bytes from the end of the first record to the next 8-byte boundary of the
            CDR payload (0 for ROS 1: nothing is aligned).
        stages: The run-time parts.
    """

    static: int
    start_gap: int
    stages: tuple[Stage, ...]

    @property
    def maximum(self) -> int:
        """The longest frame the formula can give."""
        return self.static + sum(stage.largest for stage in self.stages)


def length_formula(plan: Plan) -> LengthFormula:
    """Fold a plan's static parts and list its run-time ones.

    Raises:
        ValueError: The plan is store-and-forward (its length needs the whole frame).
    """
    if plan.store_and_forward:
        raise ValueError(f"{plan.layout.display_name}: the frame length needs the whole frame")
    steps = plan.steps
    first = steps[0]
    assert isinstance(first, Record)
    stages = []
    at = 1
    while at < len(steps):
        step = steps[at]
        if isinstance(step, Record):
            stages.append(Stage(None, 0, 0, step.size, step.align))
        elif isinstance(step, Payload) and step.length_port:
            size, align = step.element_size, step.element_align
            stages.append(Stage(step.length_port, step.maximum, size, int(step.terminator), align))
        elif isinstance(step, Payload) and step.terminator:
            stages.append(Stage(None, 0, 0, 1, 1))  # an empty CDR string still has its NUL
        elif isinstance(step, Loop):
            element = steps[at + 1]
            assert isinstance(element, Record)
            if step.count_port:
                stride = -(-element.size // element.align) * element.align
                stages.append(
                    Stage(step.count_port, step.maximum, stride, element.size, element.align, True)
                )
            at = step.next
        at += 1
    gap = (-(first.size - plan.layout.header_size)) % 8 if plan.is_cdr else 0
    return LengthFormula(first.size, gap, tuple(stages))


@block
def record_stage(
    gap_in: SignalLike, gap_out: SignalLike, pad: SignalLike, align: int, size: int
) -> Instances:
    """Padding before a record that starts at run-time positions, and the gap after it."""
    mask = align - 1

    @always_comb
    def advance() -> None:
        padding = intbv(0)[3:]
        padding[:] = gap_in & mask
        pad.next = padding
        gap_out.next = (int(gap_in) + 16 - int(padding) - size % 8) % 8

    return advance


@block
def counted_stage(
    count: SignalLike,
    gap_in: SignalLike,
    gap_out: SignalLike,
    pad: SignalLike,
    term: SignalLike,
    stage: Stage,
) -> Instances:
    """Bytes and padding of a string or sequence, and the gap after it."""
    mask = stage.align - 1
    scale, fixed, sequence = stage.scale, stage.fixed, stage.sequence
    low_bits = min(3, len(count))
    bits = len(term)  # wide enough for count * scale: no truncation in VHDL arithmetic
    # An empty sequence adds nothing; padding before elements needs at least one.
    conditional = sequence or stage.align > 1

    @always_comb
    def advance() -> None:
        low = intbv(0)[3:]
        for bit in range(low_bits):
            low[bit] = count[bit]
        padding = intbv(0)[3:]
        padding[:] = gap_in & mask
        wide = intbv(0)[bits:]
        added = 0
        if count == 0:
            if conditional:
                padding[:] = 0
            else:
                added = fixed % 8
            term.next = 0
        elif sequence:
            added = ((int(low) + 7) * scale + fixed) % 8
            wide[:] = count - 1
            term.next = wide * scale + fixed
        else:
            added = (int(low) * scale + fixed) % 8
            wide[:] = count
            term.next = wide * scale
        pad.next = padding
        gap_out.next = (int(gap_in) + 16 - int(padding) - added) % 8

    return advance


@block
def accumulate(total_in: SignalLike, term: SignalLike | int, total_out: SignalLike) -> Instances:
    """``total_out = total_in + term`` (a signal, or a constant MyHDL writes into the VHDL).

    An adder of the chain that sums the frame's terms, or a length prefix's count plus its NUL.
    """

    @always_comb
    def add() -> None:
        total_out.next = total_in + term

    return add


@block
def frame_length_circuit(
    plan: Plan, counts: dict[str, SignalLike], length: SignalLike
) -> Instances:
    """Combinational frame length of `plan` from its top-level length and count inputs.

    Args:
        plan: A plan that is neither store-and-forward nor of fixed size.
        counts: Signals of the length and count ports, by port name.
        length: Driven with the frame length in bytes.
    """
    formula = length_formula(plan)
    blocks = []
    gap = Constant(intbv(formula.start_gap)[3:])
    constant = formula.static
    terms = []
    for stage in formula.stages:
        pad, after = Signal(intbv(0)[3:]), Signal(intbv(0)[3:])
        if stage.port:
            term = Signal(intbv(0)[count_bits(stage.largest) :])
            blocks.append(counted_stage(counts[stage.port], gap, after, pad, term, stage))
            terms.append(term)
            if not stage.sequence:
                constant += stage.fixed  # a CDR string's NUL is there even when it is empty
        elif isinstance(gap, Constant):  # no run-time length before it: all known now
            padding = int(gap.val) & (stage.align - 1)
            pad = Constant(intbv(padding)[3:])
            after = Constant(intbv((int(gap.val) + 16 - padding - stage.fixed % 8) % 8)[3:])
            constant += stage.fixed
        else:
            blocks.append(record_stage(gap, after, pad, stage.align, stage.fixed))
            constant += stage.fixed
        terms.insert(0, pad)
        gap = after
    # Narrow terms first, each partial sum only as wide as it can get.
    largest = constant
    total: SignalLike = Constant(intbv(constant)[max(1, constant.bit_length()) :])
    for term in sorted(terms, key=len):
        largest += term.max - 1
        following = Signal(intbv(0)[max(1, largest.bit_length()) :])
        blocks.append(accumulate(total, term, following))
        total = following
    blocks.append(accumulate(total, Constant(intbv(0)[1:]), length))
    return blocks
