"""A plan as the constant tables a converter's control logic indexes by step number.

Both converters run one program counter (``pc``) over the plan's steps; each property of a step
(its kind, alignment, chunk count, maximum, ...) becomes a tuple indexed by ``pc``, which MyHDL
turns into a ROM. Record bytes are addressed by a *record chunk* number ``rc = base[pc] +
chunk``: chunk ``k`` of a record is its bytes ``k*W .. k*W+W-1`` on the bus lanes ``0 .. W-1``,
so every field byte has a static (rc, lane) — captured or driven without any shifter.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from rfc.lib.converters.steps import End, Loop, Next, Payload, Plan, Record, Slot


class Kind(IntEnum):
    """Step kinds as the control logic decodes them."""

    RECORD = 0
    PAYLOAD = 1
    LOOP = 2
    NEXT = 3
    END = 4


@dataclass(frozen=True)
class Piece:
    """The bytes of one slot that travel in one record chunk.

    Attributes:
        rc: Record chunk number.
        lane: First bus lane.
        count: Bytes.
        first: Index of the slot's first byte in this piece (little-endian byte order).
    """

    rc: int
    lane: int
    count: int
    first: int


@dataclass(frozen=True)
class Tables:
    """Per-step constants (tuples indexed by pc) and the numbering of chunks and streams.

    Attributes:
        kind: `Kind` of each step.
        align_mask: Record: its alignment minus one (CDR padding before it); else 0.
        chunks: Record: number of bus chunks; else 1.
        last_size: Record: bytes of its last chunk; else 0.
        base: Record: number of its first chunk; else 0.
        shift: Payload: log2 of the element size.
        terminator: Payload: 1 for a CDR string (a NUL follows the characters).
        maximum: Payload or Loop: most characters or elements accepted.
        stream: Payload: index of its sub-stream in `streams` (0 when not selected).
        selected: Payload: whether its sub-stream exists; Next: whether its channel exists.
        pieces: Payload: bus chunks per element (elements wider than the bus), else 1.
        element_mask: Payload: CDR alignment of its first element minus one.
        is_bool: Payload: whether elements are bools.
        target: Loop: the step after its Next; Next: the first step of the element.
        channel: Next: index of its element channel.
        loop: Loop and Next: index of the loop in `loops`.
        streams: Payload steps that have a sub-stream, in stream order.
        loops: Loop steps in loop order.
        record_chunks: Total chunks over all records (the range of rc).
    """

    kind: tuple[int, ...]
    align_mask: tuple[int, ...]
    chunks: tuple[int, ...]
    last_size: tuple[int, ...]
    base: tuple[int, ...]
    shift: tuple[int, ...]
    terminator: tuple[int, ...]
    maximum: tuple[int, ...]
    stream: tuple[int, ...]
    selected: tuple[int, ...]
    pieces: tuple[int, ...]
    element_mask: tuple[int, ...]
    is_bool: tuple[int, ...]
    target: tuple[int, ...]
    channel: tuple[int, ...]
    loop: tuple[int, ...]
    streams: tuple[int, ...]
    loops: tuple[int, ...]
    record_chunks: int

    @property
    def end(self) -> int:
        """The pc of the `End` step."""
        return len(self.kind) - 1


def tables(plan: Plan) -> Tables:
    """Build the per-step tables of a plan."""
    width = plan.width
    columns: dict[str, list[int]] = {name: [] for name in _COLUMNS}
    streams: list[int] = []
    loops: list[int] = []
    loop_of: dict[int, int] = {}
    chunk_count = 0
    for pc, step in enumerate(plan.steps):
        row = dict.fromkeys(_COLUMNS, 0) | {"chunks": 1, "pieces": 1}
        if isinstance(step, Record):
            count = max(1, -(-step.size // width))
            row |= {
                "kind": Kind.RECORD,
                "align_mask": step.align - 1,
                "chunks": count,
                "last_size": step.size - (count - 1) * width,
                "base": chunk_count,
            }
            chunk_count += count
        elif isinstance(step, Payload):
            if step.stream:
                row["stream"] = len(streams)
                streams.append(pc)
            row |= {
                "kind": Kind.PAYLOAD,
                "shift": step.element_size.bit_length() - 1,
                "terminator": int(step.terminator),
                "maximum": step.maximum,
                "selected": int(step.stream is not None),
                "pieces": max(1, step.element_size // width),
                "element_mask": step.element_align - 1,
                "is_bool": int(step.is_bool),
            }
        elif isinstance(step, Loop):
            loop_of[pc] = len(loops)
            loops.append(pc)
            row |= {
                "kind": Kind.LOOP,
                "maximum": step.maximum,
                "target": step.next + 1,
                "loop": loop_of[pc],
            }
        elif isinstance(step, Next):
            row |= {
                "kind": Kind.NEXT,
                "target": step.loop + 1,
                "channel": step.channel,
                "selected": int(plan.channels[step.channel].selected),
                "loop": loop_of[step.loop],
            }
        else:
            assert isinstance(step, End)
            row["kind"] = Kind.END
        for name in _COLUMNS:
            columns[name].append(int(row[name]))
    return Tables(
        **{name: tuple(values) for name, values in columns.items()},
        streams=tuple(streams),
        loops=tuple(loops),
        record_chunks=max(1, chunk_count),
    )


_COLUMNS = (
    "kind",
    "align_mask",
    "chunks",
    "last_size",
    "base",
    "shift",
    "terminator",
    "maximum",
    "stream",
    "selected",
    "pieces",
    "element_mask",
    "is_bool",
    "target",
    "channel",
    "loop",
)


def pieces(slot: Slot, base: int, width: int) -> list[Piece]:
    """Split a slot of a record whose first chunk is `base` into its per-chunk pieces."""
    result = []
    first = 0
    while first < slot.size:
        position = slot.offset + first
        lane = position % width
        count = min(slot.size - first, width - lane)
        result.append(Piece(base + position // width, lane, count, first))
        first += count
    return result
