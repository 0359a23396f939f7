"""The step walker both converters share: where the control stands in the plan, and how far.

Subscriber and publisher walk the same program (`tables`): one program counter over the steps,
the chunk of a record, a payload's remaining bytes once its length is known, the chunk of an
element wider than the bus, and the frame position modulo 8 (``gap``) that CDR alignment pads
from. The walker proposes the bytes the current step moves (``size``: a record chunk, an
alignment pad or a payload chunk) and moves on when the converter says the step goes this
cycle (``go``): the publisher when the packer has room and the stream its beat, the subscriber
when the byte window holds the bytes. The walker also counts a sequence's elements (its
loop counters); what the bytes are, the lengths and counts, and what a Next or an End waits
for stay the converter's.
"""

from __future__ import annotations

from dataclasses import dataclass

from myhdl import Constant, Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.ports import count_bits
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.tables import Kind, tables
from rfc.lib.converters.wiring import LoopControl, loop_counters
from rfc.lib.types import Instances, SignalLike


def _start_gap(plan: Plan) -> int:
    """Bytes from the frame's first byte to the next 8-byte boundary of the CDR payload."""
    return 4 if plan.is_cdr else 0


@dataclass(frozen=True)
class Walk:
    """The signals between a converter's control and its step walker.

    Attributes:
        pc: The current step.
        chunk: Record: the chunk of it the step is at.
        entered: Payload: its length is taken and `rem` holds its bytes.
        rem: Payload: bytes still to move (a CDR string's NUL included).
        piece: Payload: the chunk of the current element (elements wider than the bus).
        gap: Frame bytes moved so far, modulo 8 (from the CDR payload's first byte).
        rc: Record: the record chunk (``base + chunk``) field bytes are addressed by.
        size: Bytes the current step moves when it goes: a record chunk, an alignment pad or
            a payload chunk; 0 at any other step.
        chars: Of a payload chunk's `size`, the characters or elements (not a string's NUL).
        padding: The `size` bytes are an alignment pad (no field or element bytes).
        element_end: The payload chunk ends an element, or the payload.
        go: The converter lets the current step go this cycle.
        skip: The step has nothing to walk: a Loop no elements (the walk goes past its Next),
            a payload no bytes (the subscriber after an error).
        next_element: Next: an element is done (the walk goes on this cycle).
        loop_counts: Per Loop step, in loop order: the elements of it still to walk.
    """

    pc: SignalLike
    chunk: SignalLike
    entered: SignalLike
    rem: SignalLike
    piece: SignalLike
    gap: SignalLike
    rc: SignalLike
    size: SignalLike
    chars: SignalLike
    padding: SignalLike
    element_end: SignalLike
    go: SignalLike
    skip: SignalLike
    next_element: SignalLike
    loop_counts: tuple[SignalLike, ...]

    @classmethod
    def of(cls, plan: Plan) -> Walk:
        """The walk's signals, sized for `plan`."""
        t = tables(plan)
        pc_bits = max(1, (len(plan.steps) - 1).bit_length())
        rem_bits = count_bits(max([1, *t.maximum])) + 4
        size, chars = (Signal(intbv(0, min=0, max=plan.width + 1)) for _ in range(2))
        entered, padding, element_end, go, skip, next_element = (Signal(bool(0)) for _ in range(6))
        return cls(
            pc=Signal(intbv(0, min=0, max=2**pc_bits)),
            chunk=Signal(intbv(0, min=0, max=max(t.chunks) + 1)),
            entered=entered,
            rem=Signal(intbv(0)[rem_bits:]),
            piece=Signal(intbv(0, min=0, max=max(t.pieces) + 1)),
            gap=Signal(intbv(_start_gap(plan))[3:]),
            rc=Signal(intbv(0, min=0, max=t.record_chunks + max(t.chunks) + 1)),
            size=size,
            chars=chars,
            padding=padding,
            element_end=element_end,
            go=go,
            skip=skip,
            next_element=next_element,
            loop_counts=tuple(
                Signal(intbv(0)[count_bits(plan.loop(at).maximum) :]) for at in t.loops
            ),
        )

    def position(self) -> tuple[SignalLike, ...]:
        """pc, chunk, entered, rem, piece, gap: to bind to a block's local names."""
        return self.pc, self.chunk, self.entered, self.rem, self.piece, self.gap

    def proposal(self) -> tuple[SignalLike, ...]:
        """rc, size, chars, padding, element_end: to bind to a block's local names."""
        return self.rc, self.size, self.chars, self.padding, self.element_end


@block
def step_walker(
    plan: Plan, clk: SignalLike, rst: SignalLike, walk: Walk, count: SignalLike
) -> Instances:
    """Walk `plan`, one step's move a cycle the converter lets go (`Walk.go`).

    `count` is the current step's characters or elements, as the converter knows them. A
    record chunk or pad, or a payload chunk or pad, moves `Walk.size` bytes; a payload not yet
    entered takes the bytes of `count` elements (and a CDR string's NUL), none when
    `Walk.skip`; a Loop goes past its element when `Walk.skip`, else into it for `count`
    elements; a Next goes back while elements remain; an End starts over.
    """
    t = tables(plan)
    width = plan.width
    # A pad is at most 7 bytes: compare it with a constant its 3 bits hold (8 would read as 0).
    pad_cap = min(width, 7)
    start_gap = _start_gap(plan)
    pc, chunk, entered, rem, piece, gap = walk.position()
    rc, size, chars, padding, element_end = walk.proposal()
    go, skip = walk.go, walk.skip
    next_element = walk.next_element
    load_loop = Signal(bool(0))
    entry = Signal(intbv(0)[len(rem) :])  # the bytes the payload at pc holds: count's, a NUL
    loop_more = [Signal(bool(0)) for _ in t.loops]
    more = Signal(bool(0)) if t.loops else Constant(bool(0))
    kind_rom, align_rom, chunks_rom, last_rom, base_rom = (
        t.kind,
        t.align_mask,
        t.chunks,
        t.last_size,
        t.base,
    )
    term_rom, pieces_rom, element_rom = t.terminator, t.pieces, t.element_mask
    shift_rom, target_rom = t.shift, t.target

    @always_comb
    def propose() -> None:
        kind = kind_rom[pc]
        align = align_rom[pc]
        chunks = chunks_rom[pc]
        last_size = last_rom[pc]
        base = base_rom[pc]
        shift = shift_rom[pc]
        term = term_rom[pc]
        parts = pieces_rom[pc]
        element = element_rom[pc]

        rc.next = base + chunk
        entry.next = 0
        amount = 0
        content = 0
        is_pad = False
        pad = intbv(0)[3:]
        if kind == Kind.RECORD:
            pad[:] = gap & align
            if chunk == 0 and pad != 0:
                is_pad = True
                amount = int(pad)
                if pad > pad_cap:
                    amount = width
            elif chunk == chunks - 1:
                amount = last_size
            else:
                amount = width
        elif kind == Kind.PAYLOAD and not entered:
            entry.next = (count << shift) + term
        elif kind == Kind.PAYLOAD and rem != 0:
            pad[:] = gap & element
            if pad != 0 and piece == 0:
                is_pad = True
                amount = int(pad)
                if pad > pad_cap:
                    amount = width
            else:
                amount = width
                if rem < width:
                    amount = int(rem)
                content = amount
                if term == 1 and rem <= width:
                    content = amount - 1
        size.next = amount
        chars.next = content
        padding.next = is_pad
        element_end.next = piece == parts - 1 or rem <= width

    @always_seq(clk.posedge, reset=rst)
    def walk_on() -> None:
        kind = kind_rom[pc]
        chunks = chunks_rom[pc]
        parts = pieces_rom[pc]
        target = target_rom[pc]

        moved = 0
        if go:
            if kind == Kind.RECORD:
                moved = int(size)
                if not padding:
                    if chunk == chunks - 1:
                        pc.next = pc + 1
                        chunk.next = 0
                    else:
                        chunk.next = chunk + 1
            elif kind == Kind.PAYLOAD:
                if not entered:
                    entered.next = True
                    piece.next = 0
                    if skip:
                        rem.next = 0
                    else:
                        rem.next = entry
                elif rem == 0:
                    pc.next = pc + 1
                    entered.next = False
                else:
                    moved = int(size)
                    if not padding:
                        rem.next = rem - size
                        if piece == parts - 1:
                            piece.next = 0
                        else:
                            piece.next = piece + 1
            elif kind == Kind.LOOP:
                if skip:
                    pc.next = target
                else:
                    pc.next = pc + 1
            elif kind == Kind.NEXT:
                if more:
                    pc.next = target
                else:
                    pc.next = pc + 1
            else:
                pc.next = 0
        if kind == Kind.END:
            gap.next = start_gap
        else:
            gap.next = (int(gap) + 8 - moved) % 8

    @always_comb
    def loop_events() -> None:
        kind = kind_rom[pc]
        load_loop.next = kind == Kind.LOOP and go and not skip
        next_element.next = kind == Kind.NEXT and go

    loop_control = LoopControl(clk, rst, pc, count, load_loop, next_element)
    loops = loop_counters(plan, loop_control, list(walk.loop_counts), loop_more, more)
    return propose, walk_on, loop_events, loops
