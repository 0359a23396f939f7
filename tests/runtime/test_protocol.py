"""Chunks on the DMA streams: encoding, and reassembly of interleaved, cut messages."""

from __future__ import annotations

import itertools
import random

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rfc.runtime.protocol import (
    HEADER_SIZE,
    Chunk,
    ChunkFlags,
    ProtocolError,
    Reassembler,
    message_chunk,
    split_message,
)


def test_header_layout_is_little_endian_id_flags_length():
    chunk = message_chunk(0x0102, b"abc")
    assert chunk.to_bytes() == b"\x02\x01\x03\x00\x03\x00\x00\x00abc"
    assert HEADER_SIZE == 8
    assert Chunk.from_bytes(chunk.to_bytes()) == chunk


@st.composite
def cut_messages(draw):
    """Several messages, each cut into pieces, with the chunks of different ids interleaved."""
    messages = draw(st.dictionaries(st.integers(0, 2**16 - 1), st.binary(max_size=200), max_size=6))
    streams = []
    for ident, payload in messages.items():
        cuts = sorted(draw(st.sets(st.integers(1, max(len(payload) - 1, 1)), max_size=4)))
        edges = [0, *(c for c in cuts if c < len(payload)), len(payload)]
        sizes = [b - a for a, b in itertools.pairwise(edges)] or [0]
        streams.append(split_message(ident, payload, sizes))
    rng = random.Random(draw(st.integers(0, 2**32)))
    order = []
    cursors = [0] * len(streams)
    while any(c < len(s) for c, s in zip(cursors, streams, strict=True)):
        pick = rng.choice([i for i, s in enumerate(streams) if cursors[i] < len(s)])
        order.append(streams[pick][cursors[pick]])
        cursors[pick] += 1
    return messages, order


@given(cut_messages())
def test_interleaved_chunks_reassemble_by_id(case):
    messages, chunks = case
    reassembler = Reassembler()
    out = {}
    for chunk in chunks:
        whole = reassembler.feed(Chunk.from_bytes(chunk.to_bytes()))
        if whole is not None:
            out[chunk.id] = whole
    assert out == messages
    assert reassembler.pending() == []


def test_a_chunk_cut_by_preemption_has_no_end_flag_and_completes_by_length():
    reassembler = Reassembler()
    assert reassembler.feed(Chunk(5, ChunkFlags.START, 6, b"abc")) is None
    assert reassembler.feed(Chunk(5, ChunkFlags(0), 6, b"def")) == b"abcdef"
    assert reassembler.pending() == []


def test_orphan_continuation_is_dropped_and_counted():
    reassembler = Reassembler()
    with pytest.raises(ProtocolError, match="orphan"):
        reassembler.feed(Chunk(3, ChunkFlags.END, 4, b"abcd"))
    assert reassembler.errors == {"orphan": 1}
    assert reassembler.feed(message_chunk(3, b"ok")) == b"ok"


def test_short_and_overlong_messages():
    reassembler = Reassembler()
    first, _ = split_message(1, b"abcdef", [3, 3])
    reassembler.feed(first)
    with pytest.raises(ProtocolError, match="short"):
        reassembler.feed(Chunk(1, ChunkFlags.END, 6, b"d"))
    reassembler.feed(first)
    with pytest.raises(ProtocolError, match="overlong"):
        reassembler.feed(Chunk(1, ChunkFlags(0), 6, b"defg"))
    assert reassembler.errors == {"short": 1, "overlong": 1}
    assert reassembler.pending() == []


def test_restart_drops_the_unfinished_message():
    reassembler = Reassembler()
    reassembler.feed(split_message(7, b"abcd", [2, 2])[0])
    with pytest.raises(ProtocolError, match="restart"):
        reassembler.feed(split_message(7, b"wxyz", [2, 2])[0])
    assert reassembler.pending() == []


def test_malformed_transfers():
    with pytest.raises(ProtocolError, match="short"):
        Chunk.from_bytes(b"\x00" * 7)
    with pytest.raises(ProtocolError, match="flags"):
        Chunk.from_bytes(b"\x00\x00\x04\x00\x00\x00\x00\x00")
    with pytest.raises(ProtocolError, match="overlong"):
        Chunk.from_bytes(b"\x00\x00\x03\x00\x01\x00\x00\x00ab")


def test_split_sizes_must_cover_the_payload():
    with pytest.raises(ValueError, match="add up"):
        split_message(0, b"abc", [1, 1])
    with pytest.raises(ValueError, match="must not be empty"):
        split_message(0, b"abc", [3, 0])
    assert split_message(0, b"", [0]) == [message_chunk(0, b"")]
