"""Run a MyHDL block's converted VHDL in GHDL on vectors, through the generic cocotb benches.

`tests.support.combinational_bench` applies input vectors to a combinational block;
`tests.support.handshake_bench` streams them through a block with valid/ready handshakes, with
random idle cycles and backpressure, and measures latency. Both read a JSON job written here and
write what the hardware did back, so that the test compares it with its references in pytest.
Values cross as unsigned bit patterns of each port's width.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rfc.toolchain import run_cocotb
from rfc.toolchain.cocotb_sim import CompiledLogic, compile_logic, compiled_logic
from rfc.toolchain.ghdl import backend_named


@dataclass(frozen=True)
class HandshakeRun:
    """What the hardware produced: outputs per port, per-item latency, and when items went in.

    Attributes:
        outputs: Bit patterns (cocotb) or values (MyHDL) per output port, one per item.
        latencies: Cycles from each item's input handshake until out_valid was high.
        accepted: Cycle of each item's input handshake (differences give the initiation interval).
    """

    outputs: dict[str, list[int]]
    latencies: list[int]
    accepted: list[int]


def unsigned(value: int, width: int) -> int:
    """The bit pattern of a signed value as an unsigned integer of `width` bits."""
    return value & ((1 << width) - 1)


def signed(pattern: int, width: int) -> int:
    """The signed value of a `width`-bit pattern."""
    return pattern - (1 << width) if pattern >> (width - 1) else pattern


def _run(
    sources: Sequence[Path],
    top: str,
    bench: str,
    job: dict[str, Any],
    build: Path,
    seed: int,
    compiled: bool = False,
    simulator: str = "ghdl",
) -> dict[str, Any]:
    build.mkdir(parents=True, exist_ok=True)
    job_file = build / "job.json"
    result_file = build / "result.json"
    job_file.write_text(json.dumps({**job, "result": str(result_file)}))
    program = _program(sources, top) if compiled and simulator == "ghdl" else None
    env = {"RFC_JOB": str(job_file)}
    sim = build / "sim"
    run_cocotb(sources, top, bench, sim, env=env, seed=seed, compiled=program, simulator=simulator)
    return json.loads(result_file.read_text())


def _program(sources: Sequence[Path], top: str) -> CompiledLogic:
    """`top` compiled by GHDL's llvm back-end, once per content (tools/setup.sh installs it)."""
    backend = backend_named("llvm")
    assert backend is not None, "GHDL's llvm back-end is missing: run tools/setup.sh"
    logic = compiled_logic(sources, top, backend)
    compile_logic(logic, sources)
    return logic


def run_combinational(
    sources: Sequence[Path],
    top: str,
    inputs: Mapping[str, Sequence[int]],
    outputs: Sequence[str],
    build: Path,
    *,
    seed: int = 1,
) -> dict[str, list[int]]:
    """Apply each vector of `inputs` to `top` and return the `outputs` seen (bit patterns)."""
    job = {"inputs": {k: list(v) for k, v in inputs.items()}, "outputs": list(outputs)}
    return _run(sources, top, "tests.support.combinational_bench", job, build, seed)["outputs"]


def run_handshake(
    sources: Sequence[Path],
    top: str,
    inputs: Mapping[str, Sequence[int]],
    outputs: Sequence[str],
    build: Path,
    *,
    expected: Mapping[str, Sequence[int]] | None = None,
    idle: float = 0.3,
    backpressure: float = 0.3,
    seed: int = 1,
    timeout_cycles: int = 10_000,
    compiled: bool = False,
    simulator: str = "ghdl",
) -> HandshakeRun:
    """Stream `inputs` through `top` (in_valid/in_ready, out_valid/out_ready) and collect results.

    Args:
        sources: VHDL files in compile order.
        top: Entity with ports clk, rst, in_valid, in_ready, out_valid, out_ready and the named
            data ports.
        inputs: Bit patterns per input port, one per item.
        outputs: Output ports to record when a result is taken.
        build: Scratch folder.
        expected: Bit patterns per output port; the bench fails on the first mismatches.
        idle: Probability of holding `in_valid` low for a cycle before each item.
        backpressure: Probability of `out_ready` being low on a cycle.
        seed: Seed of the bench's random idle and backpressure.
        timeout_cycles: Cycles without progress after which the bench fails (a hang).
        compiled: In GHDL, run the logic compiled by its llvm back-end instead of mcode's: about 3
            times the cycles per second of a large block, for a compile of seconds (kept by
            content, so every run of the same logic shares it). For runs of a minute or more.
        simulator: ``ghdl`` runs the VHDL of `sources`, ``verilator`` their Verilog (a model
            built once per content): thousands of items in seconds.
    """
    job = {
        "inputs": {k: list(v) for k, v in inputs.items()},
        "outputs": list(outputs),
        "expected": {k: list(v) for k, v in (expected or {}).items()},
        "idle": idle,
        "backpressure": backpressure,
        "seed": seed,
        "timeout": timeout_cycles,
    }
    bench = "tests.support.handshake_bench"
    result = _run(sources, top, bench, job, build, seed, compiled, simulator)
    return HandshakeRun(result["outputs"], result["latencies"], result["accepted"])
