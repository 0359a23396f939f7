"""The step walker both converters share: where the control stands in the plan, and how far.

Subscriber and publisher walk the same program (`tables`): one program counter over the steps,
the chunk of a record, a payload's remaining bytes once its length is known, the chunk of an
element wider than the bus, and the frame position modulo 8 (``gap``) that CDR alignment pads
from. The walker proposes the bytes the current step moves (``size``: a record chunk, an
alignment pad or a payload chunk) and moves on when the converter says the step goes this
cycle (``go``): the publisher when the packer has room and the stream its beat, the subscriber
when the byte window holds the bytes. What the bytes are, and what a Loop or End waits for,
stays the converter's.
"""

from __future__ import annotations

from dataclasses import dataclass

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.ports import count_bits
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.tables import Kind, tables
from rfc.lib.types import Instances, SignalLike


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
        skip: Loop: it has no elements; the walk goes past its Next.
        rem_start: Payload not yet entered: the bytes it holds.
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
    rem_start: SignalLike

    @classmethod
    def of(cls, plan: Plan) -> Walk:
        """The walk's signals, sized for `plan`."""
        t = tables(plan)
        pc_bits = max(1, (len(plan.steps) - 1).bit_length())
        rem_bits = count_bits(max([1, *t.maximum])) + 4
        # Bytes from the frame's first byte to the next 8-byte boundary of the CDR payload.
        start_gap = 4 if plan.is_cdr else 0
        size, chars = (Signal(intbv(0, min=0, max=plan.width + 1)) for _ in range(2))
        entered, padding, element_end, go, skip = (Signal(bool(0)) for _ in range(5))
        rem, rem_start = (Signal(intbv(0)[rem_bits:]) for _ in range(2))
        return cls(
            pc=Signal(intbv(0, min=0, max=2**pc_bits)),
            chunk=Signal(intbv(0, min=0, max=max(t.chunks) + 1)),
            entered=entered,
            rem=rem,
            piece=Signal(intbv(0, min=0, max=max(t.pieces) + 1)),
            gap=Signal(intbv(start_gap)[3:]),
            rc=Signal(intbv(0, min=0, max=t.record_chunks + max(t.chunks) + 1)),
            size=size,
            chars=chars,
            padding=padding,
            element_end=element_end,
            go=go,
            skip=skip,
            rem_start=rem_start,
        )

    def position(self) -> tuple[SignalLike, ...]:
        """pc, chunk, entered, rem, piece, gap: to bind to a block's local names."""
        return self.pc, self.chunk, self.entered, self.rem, self.piece, self.gap

    def proposal(self) -> tuple[SignalLike, ...]:
        """rc, size, chars, padding, element_end: to bind to a block's local names."""
        return self.rc, self.size, self.chars, self.padding, self.element_end

    def decision(self) -> tuple[SignalLike, ...]:
        """go, skip, rem_start: to bind to a block's local names."""
        return self.go, self.skip, self.rem_start


@block
def step_walker(
    plan: Plan, clk: SignalLike, rst: SignalLike, walk: Walk, more: SignalLike
) -> Instances:
    """Walk `plan`, one step's move a cycle the converter lets go (`Walk.go`).

    A record chunk or pad, or a payload chunk or pad, moves `Walk.size` bytes; a payload not
    yet entered takes `Walk.rem_start` bytes; a Loop goes past its element when `Walk.skip`,
    else into it; a Next goes back for the next element while `more`; an End starts over.
    """
    t = tables(plan)
    width = plan.width
    # A pad is at most 7 bytes: compare it with a constant its 3 bits hold (8 would read as 0).
    pad_cap = min(width, 7)
    start_gap = 4 if plan.is_cdr else 0
    pc, chunk, entered, rem, piece, gap = walk.position()
    rc, size, chars, padding, element_end = walk.proposal()
    go, skip, rem_start = walk.decision()
    kind_rom, align_rom, chunks_rom, last_rom, base_rom = (
        t.kind,
        t.align_mask,
        t.chunks,
        t.last_size,
        t.base,
    )
    term_rom, pieces_rom, element_rom, target_rom = t.terminator, t.pieces, t.element_mask, t.target

    @always_comb
    def propose() -> None:
        kind = kind_rom[pc]
        align = align_rom[pc]
        chunks = chunks_rom[pc]
        last_size = last_rom[pc]
        base = base_rom[pc]
        term = term_rom[pc]
        parts = pieces_rom[pc]
        element = element_rom[pc]

        rc.next = base + chunk
        amount = 0
        count = 0
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
        elif kind == Kind.PAYLOAD and entered and rem != 0:
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
                count = amount
                if term == 1 and rem <= width:
                    count = amount - 1
        size.next = amount
        chars.next = count
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
                    rem.next = rem_start
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

    return propose, walk_on
