"""Field registers of the subscriber: each byte captured from a fixed lane of a fixed chunk.

A field's bytes arrive in one or more bus chunks, a run of contiguous lanes in each
(`tables.pieces`). Each run has its own register, loaded with a constant slice of the chunk
when its chunk passes: no multiplexer, no variable index (which synthesis reads as a shifter
over the whole bus per bit), only a chunk-number compare; the field is the runs side by side.
A field that fills whole chunks in a row (every field on an 8-bit bus) is instead shifted in
a chunk at a time: one register and one process, not one per chunk.

The subscriber walks a record's chunks in order, each firing once per pass (padding chunks
hold no field byte), so both forms hold a field's bytes from the edge its last chunk passes.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, concat, intbv

from rfc.lib.converters.steps import Plan, Slot, SlotRole
from rfc.lib.converters.tables import Piece, pieces, tables
from rfc.lib.types import Instances, SignalLike


@block
def run_register(
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    rc: SignalLike,
    data: SignalLike,
    at: int,
    lane: int,
    target: SignalLike,
) -> Instances:
    """Capture `target` from the bytes of `data` from lane `lane` up when chunk `at` passes.

    A one-bit `target` is a bool, one byte on the wire: it takes whether that byte is not zero
    (rosbags reads any nonzero byte as true).
    """
    low = 8 * lane
    if len(target) == 1:

        @always_seq(clk.posedge, reset=rst)
        def capture() -> None:
            if fire and rc == at:
                target.next = data[low + 8 : low] != 0

    else:
        high = low + len(target)

        @always_seq(clk.posedge, reset=rst)
        def capture() -> None:
            if fire and rc == at:
                target.next = data[high:low]

    return capture


@block
def shift_register(
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    rc: SignalLike,
    data: SignalLike,
    first: int,
    last: int,
    target: SignalLike,
) -> Instances:
    """Shift whole chunks `first` to `last` into `target` as they pass, the first lowest.

    GHDL runs a clocked process at every clock edge: an 8-byte field on an 8-bit bus takes
    one here instead of eight, and FrankaState's converter pair 392 instead of 2,494.
    """
    step, top = len(data), len(target)

    @always_seq(clk.posedge, reset=rst)
    def shift_in() -> None:
        if fire and rc >= first and rc <= last:
            target.next = concat(data, target[top:step])

    return shift_in


def _whole_chunks_in_a_row(runs: tuple[Piece, ...], chunk_bytes: int) -> bool:
    """Whether the runs are whole chunks, one after the other, in the field's byte order."""
    return len(runs) > 1 and all(
        run.lane == 0 and run.count == chunk_bytes and run.rc == runs[0].rc + i
        for i, run in enumerate(runs)
    )


@block
def field_register(
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    rc: SignalLike,
    data: SignalLike,
    runs: tuple[Piece, ...],
    target: SignalLike,
) -> Instances:
    """Capture `target` from its runs: bytes ``first ..`` from lanes ``lane ..`` of chunk ``rc``.

    A field in one run (a bool among them) is captured straight into `target`, one in whole
    chunks in a row shifted into it (`shift_register`); any other has a register per run
    (reset to its part of `target`'s reset value), joined into `target` by wires, so it still
    changes on the clock edge its last run is captured on. The join is a process of its own
    rather than `wiring.follow`: MyHDL numbers a block's instances across the process, and more
    `follow`s here would rename those of every block built after the converters.
    """
    octets = sum(run.count for run in runs)
    assert len(target) == 8 * octets or len(target) == octets == 1, "a byte per octet, or a bool"
    if len(runs) == 1:
        return run_register(clk, rst, fire, rc, data, runs[0].rc, runs[0].lane, target)
    if _whole_chunks_in_a_row(runs, len(data) // 8):
        return shift_register(clk, rst, fire, rc, data, runs[0].rc, runs[-1].rc, target)
    reset = int(target.val)
    parts = [
        Signal(intbv((reset >> (8 * run.first)) & ((1 << (8 * run.count)) - 1))[8 * run.count :])
        for run in runs
    ]
    blocks = [
        run_register(clk, rst, fire, rc, data, run.rc, run.lane, part)
        for run, part in zip(runs, parts, strict=True)
    ]
    joined = ConcatSignal(*reversed(parts))

    @always_comb
    def join() -> None:
        target.next = joined

    blocks.append(join)
    return blocks


# A plan, its ports and the control's signals, as every part of a converter takes them.
@block
def field_captures(
    plan: Plan,
    ports: dict[str, SignalLike],
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    rc: SignalLike,
    data: SignalLike,
    header: SignalLike,
) -> Instances:
    """Capture every selected field of the plan, and the CDR header's first two bytes.

    Args:
        plan: The converter's plan.
        ports: The converter's port signals by name.
        clk: Clock.
        rst: Reset.
        fire: A record chunk is consumed this cycle.
        rc: Its record chunk number.
        data: The chunk's bytes (lane 0 low).
        header: Receives the CDR encapsulation's first two bytes.
    """
    t = tables(plan)
    registers = []
    for pc, step in plan.records():
        for slot in step.slots:
            if slot.role is SlotRole.ENCAPSULATION:
                target = header
                slot = Slot(slot.offset, 2, slot.role)
            elif slot.role is SlotRole.FIELD and slot.port:
                target = ports[slot.port]
            else:
                continue
            runs = tuple(pieces(slot, t.base[pc], plan.width))
            registers.append(field_register(clk, rst, fire, rc, data, runs, target))
    return registers
