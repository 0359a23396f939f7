"""chunk_mux in GHDL with each scheduler: messages reassemble byte-exact, chunks follow the
protocol, and the grants are the scheduler model's on every cycle."""

from __future__ import annotations

import json
import random

import numpy as np
import pytest
from myhdl import ResetSignal, Signal, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.manager.mux import chunk_mux
from rfc.lib.schedulers.model import model_of
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.runtime.protocol import HEADER_SIZE, Chunk, ChunkFlags, Reassembler
from rfc.toolchain import convert_myhdl, elaboration, run_cocotb

PUBLISHERS = 3


def mux_files(spec, width, directory):
    lanes = width // 8
    n = spec.n

    def vector(bits):
        return Signal(intbv(0)[bits:])

    @block
    def top(
        clk,
        rst,
        s_tdata,
        s_tkeep,
        s_tvalid,
        s_tready,
        s_tlast,
        s_length,
        m_tdata,
        m_tkeep,
        m_tvalid,
        m_tready,
        m_tlast,
    ):
        return chunk_mux(
            clk,
            rst,
            AxiStream(s_tdata, s_tkeep, s_tvalid, s_tready, s_tlast),
            s_length,
            AxiStream(m_tdata, m_tkeep, m_tvalid, m_tready, m_tlast),
            width=width,
            scheduler=spec,
        )

    with elaboration():
        instance = top(
            Signal(bool(0)),
            ResetSignal(0, active=1, isasync=False),
            vector(n * width),
            vector(n * lanes),
            vector(n),
            vector(n),
            vector(n),
            vector(n * 32),
            vector(width),
            vector(lanes),
            Signal(bool(0)),
            Signal(bool(0)),
            Signal(bool(0)),
        )
        return convert_myhdl(instance, "mux", directory, verilog=False)


def check_chunks(chunks, messages, preemptive):
    reassembler = Reassembler()
    received = [[] for _ in messages]
    for raw in chunks:
        chunk = Chunk.from_bytes(bytes.fromhex(raw))
        assert len(bytes.fromhex(raw)) >= HEADER_SIZE
        if not preemptive:
            assert chunk.flags == ChunkFlags.WHOLE
            assert len(chunk.payload) == chunk.length
        else:
            assert ChunkFlags.END not in chunk.flags
        whole = reassembler.feed(chunk)
        if whole is not None:
            received[chunk.id].append(whole.hex())
    assert received == messages
    assert reassembler.pending() == []
    # Chunks beyond one per message are cuts made by preemption.
    return len(chunks) - sum(len(m) for m in messages)


def replay_model(spec, trace):
    model = model_of(spec)
    n = spec.n
    for cycle, grant in enumerate(trace["grant"]):
        request = np.array([[trace["request"][cycle] >> i & 1 for i in range(n)]], dtype=bool)
        last = np.array([[trace["last"][cycle] >> i & 1 for i in range(n)]], dtype=bool)
        ready = np.array([bool(trace["ready"][cycle])])
        expected = model.step(request, last, ready)[0]
        got = grant.bit_length() - 1 if grant else -1
        assert got == expected, f"cycle {cycle}: hardware granted {got}, model {expected}"


@pytest.mark.parametrize(
    ("algorithm", "width"),
    [(a, 64) for a in Algorithm] + [(Algorithm.LST, 8), (Algorithm.LRU, 32)],
)
def test_mux_carries_every_message_with_the_schedulers_grants(tmp_path, algorithm, width):
    rng = random.Random(f"{algorithm}{width}")
    spec = SchedulerSpec.create(algorithm, PUBLISHERS, transfer=[6, 12, 3], deadline=[40, 60, 30])
    messages = [
        [rng.randbytes(rng.choice([1, 5, 8, 17, rng.randrange(1, 90)])).hex() for _ in range(12)]
        for _ in range(PUBLISHERS)
    ]
    result = tmp_path / "result.json"
    case = {
        "seed": rng.randrange(2**32),
        "width": width,
        "publishers": PUBLISHERS,
        "messages": messages,
        "bubble": 0.15,
        "gap": 30,
        "backpressure": 0.25,
        "max_cycles": 40_000,
        "result": str(result),
    }
    files = mux_files(spec, width, tmp_path / "hdl")
    case["ready_signal"] = "chunk_mux0_ready"  # MyHDL prefixes internal names by instance
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    run_cocotb(
        files,
        "mux",
        "tests.hdl.manager.mux_bench",
        tmp_path / "sim",
        env={"RFC_BENCH_CASE": str(path)},
    )
    outcome = json.loads(result.read_text())
    cuts = check_chunks(outcome["chunks"], messages, algorithm.preemptive)
    # The traffic contends enough that every preemptive scheduler cuts some message.
    assert (cuts > 0) == algorithm.preemptive
    replay_model(spec, outcome["trace"])
