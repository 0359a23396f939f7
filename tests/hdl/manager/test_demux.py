"""chunk_demux in GHDL: valid chunks reach their subscriber byte-exact; bad ones are counted."""

from __future__ import annotations

import json
import random

import pytest
from myhdl import ResetSignal, Signal, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.manager.demux import chunk_demux
from rfc.runtime.protocol import Chunk, ChunkFlags, message_chunk
from rfc.toolchain import convert_myhdl, run_cocotb

SUBSCRIBERS = 3


def demux_files(width, directory):
    lanes = width // 8

    def vector(bits):
        return Signal(intbv(0)[bits:])

    instance = chunk_demux(
        Signal(bool(0)),
        ResetSignal(0, active=1, isasync=False),
        AxiStream(vector(width), vector(lanes), Signal(bool(0)), Signal(bool(0)), Signal(bool(0))),
        AxiStream(
            vector(width), vector(lanes), vector(SUBSCRIBERS), vector(SUBSCRIBERS), Signal(bool(0))
        ),
        vector(16),
        width=width,
        subscribers=SUBSCRIBERS,
    )
    return convert_myhdl(instance, "demux", directory, verilog=False)


def traffic(rng, count):
    """Valid chunks for random subscribers mixed with every kind of bad chunk."""
    chunks, expected, errors = [], [[] for _ in range(SUBSCRIBERS)], 0
    null_beats = [0] * SUBSCRIBERS
    for _ in range(count):
        kind = rng.choice(["valid"] * 6 + ["empty", "unknown", "flags", "length", "cut"])
        ident = rng.randrange(SUBSCRIBERS)
        payload = rng.randbytes(rng.choice([1, 3, 8, rng.randrange(1, 300)]))
        if kind == "valid":
            chunks.append(message_chunk(ident, payload).to_bytes())
            expected[ident].append(payload.hex())
        elif kind == "empty":
            chunks.append(message_chunk(ident, b"").to_bytes())
            expected[ident].append("")
            null_beats[ident] += 1
        elif kind == "unknown":
            chunks.append(message_chunk(SUBSCRIBERS + rng.randrange(100), payload).to_bytes())
            errors += 1
        elif kind == "flags":
            chunks.append(Chunk(ident, ChunkFlags.START, len(payload), payload).to_bytes())
            errors += 1
        elif kind == "length":
            # Delivered (the converter checks the message itself) but counted.
            chunks.append(Chunk(ident, ChunkFlags.WHOLE, len(payload) + 1, payload).to_bytes())
            expected[ident].append(payload.hex())
            errors += 1
        else:
            chunks.append(message_chunk(ident, payload).to_bytes()[: rng.randrange(1, 8)])
            errors += 1
    return chunks, expected, null_beats, errors


@pytest.mark.parametrize("width", [8, 32, 64])
def test_demux_routes_chunks_and_counts_bad_ones(tmp_path, width):
    rng = random.Random(width)
    chunks, expected, null_beats, errors = traffic(rng, 120)
    case = {
        "seed": width,
        "width": width,
        "subscribers": SUBSCRIBERS,
        "idle": 0.2,
        "backpressure": 0.3,
        "chunks": [c.hex() for c in chunks],
        "expected": expected,
        "null_beats": null_beats,
        "errors": errors,
    }
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    files = demux_files(width, tmp_path / "hdl")
    run_cocotb(
        files,
        "demux",
        "tests.hdl.manager.demux_bench",
        tmp_path / "sim",
        env={"RFC_BENCH_CASE": str(path)},
    )
