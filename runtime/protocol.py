"""The wire protocol between processor and logic: chunks on the two DMA streams (docs/protocol.md).

Every DMA transfer is one *chunk*: an 8-byte little-endian header — ``u16 id`` (subscriber or
publisher index), ``u16 flags`` (bit 0 START, bit 1 END), ``u32 length`` (the whole message's
payload length) — followed by payload bytes. PS→PL chunks always carry a whole message
(START|END). PL→PS, a preemptive scheduler may cut a message into several chunks, which
`Reassembler` puts back together by id.

The logic writes a chunk's header before its payload, so it cannot always know that a chunk will
end its message: preemption may cut it at any beat. START is always exact (the manager knows
whether the publisher already sent part of the message); END is set when the chunk is known at
its start to finish the message (always, for non-preemptive schedulers). A message is complete
when its bytes reach `length`; END, when set, must agree.
"""

from __future__ import annotations

import struct
from collections.abc import Iterable
from dataclasses import dataclass, field
from enum import IntFlag
from typing import NoReturn

HEADER = struct.Struct("<HHI")
HEADER_SIZE = HEADER.size
#: The id of status chunks: the processor's request for the logic's drop counters, and the
#: logic's answer (`rfc.runtime.status`). No subscriber or publisher has it.
STATUS_ID = 0xFFFF


class ChunkFlags(IntFlag):
    """Where a chunk sits in its message."""

    START = 1
    END = 2
    WHOLE = START | END


class ProtocolError(ValueError):
    """A chunk that breaks the protocol; `reason` is a short stable code for counters."""

    def __init__(self, reason: str, detail: str) -> None:
        super().__init__(f"{reason}: {detail}")
        self.reason = reason


@dataclass(frozen=True)
class Chunk:
    """One DMA transfer: header fields and this chunk's share of the payload."""

    id: int
    flags: ChunkFlags
    length: int
    payload: bytes

    @property
    def size(self) -> int:
        """Bytes of the transfer: header and payload."""
        return HEADER_SIZE + len(self.payload)

    def to_bytes(self) -> bytes:
        """Serialize header and payload, as the DMA moves them."""
        return HEADER.pack(self.id, int(self.flags), self.length) + self.payload

    @classmethod
    def from_bytes(cls, transfer: bytes | memoryview) -> Chunk:
        """Parse one DMA transfer.

        Raises:
            ProtocolError: Shorter than a header, unknown flag bits, or more payload than the
                message length.
        """
        if len(transfer) < HEADER_SIZE:
            raise ProtocolError("short", f"{len(transfer)} bytes cannot hold a chunk header")
        ident, flags, length = HEADER.unpack_from(transfer)
        if flags & ~int(ChunkFlags.WHOLE):
            raise ProtocolError("flags", f"chunk for id {ident} has unknown flag bits {flags:#x}")
        payload = bytes(transfer[HEADER_SIZE:])
        if len(payload) > length:
            raise ProtocolError(
                "overlong", f"chunk for id {ident} carries {len(payload)} bytes of a {length}"
            )
        return cls(ident, ChunkFlags(flags), length, payload)


def message_chunk(ident: int, payload: bytes) -> Chunk:
    """The single chunk that carries a whole message (every PS→PL transfer)."""
    return Chunk(ident, ChunkFlags.WHOLE, len(payload), payload)


def split_message(ident: int, payload: bytes, sizes: Iterable[int]) -> list[Chunk]:
    """Cut a message into chunks of the given payload sizes (how a preempted publisher appears).

    The sizes must add up to the payload length; zero-size pieces are not allowed except for an
    empty message.
    """
    chunks: list[Chunk] = []
    start = 0
    pieces = list(sizes)
    if sum(pieces) != len(payload):
        raise ValueError(f"piece sizes add up to {sum(pieces)}, not {len(payload)}")
    if payload and min(pieces) <= 0:
        raise ValueError(f"pieces of a non-empty message must not be empty: {pieces}")
    for index, size in enumerate(pieces):
        flags = ChunkFlags(0)
        if index == 0:
            flags |= ChunkFlags.START
        if index == len(pieces) - 1:
            flags |= ChunkFlags.END
        chunks.append(Chunk(ident, flags, len(payload), payload[start : start + size]))
        start += size
    return chunks


@dataclass
class _Partial:
    length: int
    parts: list[bytes] = field(default_factory=list)
    received: int = 0


class Reassembler:
    """Rebuilds messages from PL→PS chunks, keyed by id; chunks of different ids may interleave.

    A protocol violation drops the affected message, counts it by reason, and raises
    `ProtocolError`; the reassembler stays usable for every other id and for the next message.
    """

    def __init__(self) -> None:
        self._open: dict[int, _Partial] = {}
        self.errors: dict[str, int] = {}

    def feed(self, chunk: Chunk) -> bytes | None:
        """Take one chunk; return the whole message when this chunk completes it."""
        partial = self._open.get(chunk.id)
        if ChunkFlags.START in chunk.flags:
            if partial is not None:
                del self._open[chunk.id]
                self._fail("restart", f"id {chunk.id} started a message before ending the last")
            partial = self._open[chunk.id] = _Partial(chunk.length)
        elif partial is None:
            self._fail("orphan", f"id {chunk.id} continued a message it never started")
        elif chunk.length != partial.length:
            del self._open[chunk.id]
            self._fail("length", f"id {chunk.id} changed length {partial.length}→{chunk.length}")
        partial.parts.append(chunk.payload)
        partial.received += len(chunk.payload)
        if partial.received > partial.length:
            del self._open[chunk.id]
            self._fail("overlong", f"id {chunk.id} sent more than {partial.length} bytes")
        if partial.received < partial.length:
            if ChunkFlags.END in chunk.flags:
                del self._open[chunk.id]
                self._fail("short", f"id {chunk.id} ended at {partial.received}/{partial.length}")
            return None
        del self._open[chunk.id]
        return b"".join(partial.parts)

    def pending(self) -> list[int]:
        """Ids with a message started and not yet ended."""
        return sorted(self._open)

    def _fail(self, reason: str, detail: str) -> NoReturn:
        self.errors[reason] = self.errors.get(reason, 0) + 1
        raise ProtocolError(reason, detail)
