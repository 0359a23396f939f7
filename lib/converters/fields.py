"""Field registers of the subscriber: each byte captured from a fixed lane of a fixed chunk.

A field's bytes arrive in one or more bus chunks; byte ``b`` comes from lane ``lanes[b]`` of
record chunk ``chunks[b]`` (`tables.pieces`). The register writes it when that chunk passes: no
multiplexer is involved, only a chunk-number compare, and one process serves the whole field.
"""

from __future__ import annotations

from myhdl import always_seq, block

from rfc.lib.converters.steps import Plan, Slot, SlotRole
from rfc.lib.converters.tables import pieces, tables
from rfc.lib.types import Instances, SignalLike


@block
def field_register(
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    rc: SignalLike,
    data: SignalLike,
    chunks: tuple[int, ...],
    lanes: tuple[int, ...],
    target: SignalLike,
) -> Instances:
    """Capture byte ``b`` of `target` from lane ``lanes[b]`` of `data` at chunk ``chunks[b]``."""
    size = len(chunks)

    @always_seq(clk.posedge, reset=rst)
    def capture() -> None:
        if fire:
            for byte in range(size):
                at = chunks[byte]
                lane = lanes[byte]
                if rc == at:
                    for bit in range(8):
                        target.next[8 * byte + bit] = data[8 * lane + bit]

    return capture


@block
def bool_register(
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    rc: SignalLike,
    data: SignalLike,
    at: int,
    lane: int,
    target: SignalLike,
) -> Instances:
    """Capture a bool: whether the byte on `lane` of chunk `at` is not zero."""
    low = 8 * lane

    @always_seq(clk.posedge, reset=rst)
    def capture() -> None:
        if fire and rc == at:
            target.next = data[low + 8 : low] != 0

    return capture


def _byte_sources(slot: Slot, base: int, width: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """Record chunk and lane of each byte of a slot whose record starts at chunk `base`."""
    runs = pieces(slot, base, width)
    chunks = tuple(run.rc for run in runs for _ in range(run.count))
    lanes = tuple(run.lane + i for run in runs for i in range(run.count))
    return chunks, lanes


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
            chunks, lanes = _byte_sources(slot, t.base[pc], plan.width)
            if slot.field is not None and slot.field.element_type == "bool":
                registers.append(
                    bool_register(clk, rst, fire, rc, data, chunks[0], lanes[0], target)
                )
            else:
                registers.append(field_register(clk, rst, fire, rc, data, chunks, lanes, target))
    return registers
