"""The logic's drop counters as the processor reads them: a status chunk on the DMA streams.

The processor sends an empty chunk of id `STATUS_ID` (`status_request`); between two of its
publishers' chunks the logic answers with a chunk of the same id holding one little-endian
``u32`` per (subscriber, reason), subscriber by subscriber in id order, the reasons in the
order of `STATUS_REASONS` (docs/protocol.md, "Status registers"). This works through the one
DMA the node already drives, on the board and in simulation alike. The counts run from the
logic's reset, so a later reading replaces an earlier one.
"""

from __future__ import annotations

import struct
from collections.abc import Iterable

from rfc.runtime.protocol import HEADER, STATUS_ID, Chunk, ChunkFlags, ProtocolError

#: Why a subscriber dropped a frame, in the order of each subscriber's counters
#: (`rfc.lib.converters.malformed.DROP_REASONS`).
STATUS_REASONS = ("truncated", "maximum", "trailing", "encoding")


def status_request() -> Chunk:
    """The chunk that asks the logic for its counters."""
    return Chunk(STATUS_ID, ChunkFlags.WHOLE, 0, b"")


def is_status(transfer: bytes) -> bool:
    """Whether a PL→PS transfer is the logic's status answer (by its id)."""
    return len(transfer) >= HEADER.size and HEADER.unpack_from(transfer)[0] == STATUS_ID


def decode_status(transfer: bytes, subscribers: Iterable[int]) -> dict[tuple[int, str], int]:
    """The drop counts of a status answer, by (subscriber id, reason).

    Args:
        transfer: The PL→PS transfer (header and payload).
        subscribers: The logic's subscriber ids (0 … n-1).

    Raises:
        ProtocolError: The answer is not whole or its length does not fit the subscribers
            (``status``).
    """
    ids = sorted(subscribers)
    chunk = Chunk.from_bytes(transfer)
    expected = 4 * len(STATUS_REASONS) * len(ids)
    whole = chunk.flags == ChunkFlags.WHOLE and chunk.length == len(chunk.payload)
    if not whole or chunk.length != expected:
        raise ProtocolError(
            "status",
            f"a status answer of {len(chunk.payload)} of {chunk.length} bytes, not the "
            f"{expected} bytes of {len(ids)} subscribers",
        )
    values = struct.unpack(f"<{len(STATUS_REASONS) * len(ids)}I", chunk.payload)
    keys = [(ident, reason) for ident in ids for reason in STATUS_REASONS]
    return dict(zip(keys, values, strict=True))
