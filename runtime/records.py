"""Published messages in a file: how a simulation hands its results to the parent process.

The format is private to rfc and short-lived (one run): per message a little-endian u32
length of a JSON header (topic, message type, stamp), the header, a u64 payload length and
the payload bytes.
"""

from __future__ import annotations

import json
import struct
from collections.abc import Iterable, Iterator
from pathlib import Path

from rfc.runtime.core import Published

_HEADER_LENGTH = struct.Struct("<I")
_PAYLOAD_LENGTH = struct.Struct("<Q")


def write_records(path: Path, messages: Iterable[Published]) -> None:
    """Write messages to `path` (replacing it)."""
    with path.open("wb") as stream:
        for message in messages:
            header = json.dumps(
                {"topic": message.topic, "message": message.message, "stamp": message.stamp}
            ).encode()
            stream.write(_HEADER_LENGTH.pack(len(header)) + header)
            stream.write(_PAYLOAD_LENGTH.pack(len(message.data)) + message.data)


def read_records(path: Path) -> Iterator[Published]:
    """Read the messages `write_records` wrote, in order."""
    with path.open("rb") as stream:
        while prefix := stream.read(_HEADER_LENGTH.size):
            (size,) = _HEADER_LENGTH.unpack(prefix)
            header = json.loads(stream.read(size))
            (length,) = _PAYLOAD_LENGTH.unpack(stream.read(_PAYLOAD_LENGTH.size))
            data = stream.read(length)
            yield Published(header["topic"], header["message"], header["stamp"], data)
