"""Benchmark: the Quaternion→Euler accelerator's latency, throughput, size and accuracy.

Latency and initiation interval come from GHDL (cocotb) running the converted VHDL with no idle
cycles and no backpressure; LUT/FF/DSP from Yosys (`synth_xilinx`, 7-series); accuracy from the
bit-accurate reference (bit-exact with the hardware, as the tests prove) against NumPy over a
large random set. Anchors: the paper's HLS core took 373 cycles; target ≤ 120
cycles and ≤ 1e-9 rad (1e-5 within 1e-3 rad of gimbal lock).

Usage: .venv/bin/python tools/bench_quat_to_euler.py [--core pipelined|iterative] [--samples N]
       [--items N] [--no-synth]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the cocotb benches and test orientations live under tests/

from rfc.lib.fixed import bits_to_float, float_to_bits  # noqa: E402
from rfc.toolchain import convert_myhdl, estimate_resources  # noqa: E402
from tests.examples.quaternion_to_euler.example import (  # noqa: E402
    Core,
    core_arguments,
    core_ports,
    cores,
    example,
)
from tests.examples.quaternion_to_euler.quaternions import (  # noqa: E402
    GIMBAL_ZONE,
    LOCKED,
    angle_error,
    exact_cos_pitch,
    gimbal_neighbourhood,
    uniform,
)
from tests.support.cosim import run_handshake  # noqa: E402

numpy_reference = example().numpy_reference

PAPER_CYCLES = 373
TARGET_CYCLES = 120
TARGET_ERROR = 1e-9


def timing(files: list[Path], items: int, work: Path) -> tuple[list[int], list[int]]:
    quaternions = uniform(items, np.random.default_rng(1))
    inputs = {a: [float_to_bits(float(v)) for v in quaternions[:, i]] for i, a in enumerate("xyzw")}
    run = run_handshake(files, "quat_to_euler", inputs, ["roll"], work, idle=0.0, backpressure=0.0)
    return run.latencies, list(np.diff(run.accepted))


def accuracy(core: Core, samples: int) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(7)
    sets = {
        "uniform": uniform(samples, rng),
        "gimbal zone": gimbal_neighbourhood(samples // 10, rng),
    }
    worst = {}
    for name, quaternions in sets.items():
        rows = [core.reference(q) for q in quaternions]
        hardware = np.array([[bits_to_float(b) for b in row] for row in rows])
        want = numpy_reference(quaternions)
        error = angle_error(hardware, want)
        locked = exact_cos_pitch(quaternions) < LOCKED
        zone = np.abs(want[:, 1]) > np.pi / 2 - GIMBAL_ZONE
        keep = ~locked & (zone if name == "gimbal zone" else ~zone)
        worst[name] = error[keep].max(axis=0)
    return worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=100_000, help="random quaternions")
    parser.add_argument("--items", type=int, default=20, help="quaternions through GHDL")
    parser.add_argument("--no-synth", action="store_true", help="skip Yosys")
    parser.add_argument("--core", choices=["pipelined", "iterative"], default="pipelined")
    args = parser.parse_args()
    core = next(c for c in cores() if c.name == args.core)
    with tempfile.TemporaryDirectory(prefix="rfc-bench-q2e-") as scratch:
        work = Path(scratch)
        files = convert_myhdl(
            core.block(*core_arguments(core_ports())), "quat_to_euler", work / "hdl"
        )
        latencies, intervals = timing(files, args.items, work / "sim")
        latency = max(latencies)
        print(
            f"latency             {min(latencies)}..{latency} cycles   target <= {TARGET_CYCLES}"
            f"   ratio to paper {latency / PAPER_CYCLES:.3f} ({PAPER_CYCLES})"
        )
        print(f"initiation interval {min(intervals)}..{max(intervals)} cycles")
        if not args.no_synth:
            start = time.perf_counter()
            cells = estimate_resources(files, "quat_to_euler")
            seconds = time.perf_counter() - start
            print(
                f"resources           {cells.lut} LUT, {cells.ff} FF, {cells.carry} CARRY4, "
                f"{cells.dsp} DSP48E1, {cells.bram} BRAM  (yosys {seconds:.0f} s)"
            )
    start = time.perf_counter()
    for name, worst in accuracy(core, args.samples).items():
        roll, pitch, yaw = (f"{e:.2e}" for e in worst)
        print(
            f"max error {name:11s} roll {roll}  pitch {pitch}  yaw {yaw} rad"
            f"   target <= {TARGET_ERROR if name == 'uniform' else 1e-5:g}"
        )
    print(
        f"({args.samples} uniform + {args.samples // 10} gimbal-zone samples, "
        f"{time.perf_counter() - start:.0f} s)"
    )


if __name__ == "__main__":
    main()
