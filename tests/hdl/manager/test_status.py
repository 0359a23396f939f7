"""status_inserter in GHDL: each request gets one status chunk of the counters as they were,
and the publishers' chunks around it pass whole and in order."""

from __future__ import annotations

import json
import random
import struct

import pytest
from myhdl import ResetSignal, Signal, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.manager.status import status_inserter
from rfc.runtime.protocol import HEADER, message_chunk
from rfc.toolchain import convert_myhdl, run_cocotb

COUNTERS = 8  # two subscribers, four reasons each


def inserter_files(width, directory):
    lanes = width // 8

    def vector(bits):
        return Signal(intbv(0)[bits:])

    def stream():
        return AxiStream(vector(width), vector(lanes), *(Signal(bool(0)) for _ in range(3)))

    instance = status_inserter(
        Signal(bool(0)),
        ResetSignal(0, active=1, isasync=False),
        Signal(bool(0)),
        vector(32 * COUNTERS),
        stream(),
        stream(),
        width=width,
        count=COUNTERS,
    )
    return convert_myhdl(instance, "inserter", directory, verilog=False)


@pytest.mark.parametrize("width", [8, 32, 64])
def test_each_request_is_answered_between_whole_chunks(tmp_path, width):
    rng = random.Random(width)
    chunks = [
        message_chunk(rng.randrange(3), rng.randbytes(rng.randrange(1, 60))).to_bytes()
        for _ in range(40)
    ]
    readings = [[rng.randrange(2**32) for _ in range(COUNTERS)] for _ in range(12)]
    result = tmp_path / "result.json"
    case = {
        "seed": width,
        "chunks": [c.hex() for c in chunks],
        "readings": readings,
        "idle": 0.3,
        "backpressure": 0.3,
        "result": str(result),
    }
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    files = inserter_files(width, tmp_path / "hdl")
    run_cocotb(
        files,
        "inserter",
        "tests.hdl.manager.status_bench",
        tmp_path / "sim",
        env={"RFC_BENCH_CASE": str(path)},
    )
    frames = [bytes.fromhex(f) for f in json.loads(result.read_text())]
    answers = [f for f in frames if HEADER.unpack_from(f)[0] == 0xFFFF]
    # the layout docs/protocol.md gives, packed by struct
    expected = [
        struct.pack("<HHI", 0xFFFF, 3, 4 * COUNTERS) + struct.pack(f"<{COUNTERS}I", *reading)
        for reading in readings
    ]
    assert answers == expected
    assert [f for f in frames if f not in answers] == chunks
    # the requests came while chunks were flowing: the first answer is not after all of them
    assert frames.index(answers[0]) < len(chunks)
