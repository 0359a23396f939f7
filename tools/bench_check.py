"""Benchmark: `rfc check` on a generated 200-block spec.

Target (issue 3): under 2 s for the whole command (process start, YAML front-end, every pass).
The spec has 40 chains subscriber → 3 accelerators → publisher over four message types
(Quaternion/Point, Image with include lists, Odometry, TFMessage), so every pass has work.
Also prints the in-process time of the front-end and of each pass.

Usage: .venv/bin/python tools/bench_check.py [--chains N] [--repeat N]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET_S = 2.0
KINDS = (
    ("geometry_msgs/Quaternion", "geometry_msgs/Point", ""),
    ("sensor_msgs/Image", "sensor_msgs/Image", ", include: [header, height, width, data]"),
    ("nav_msgs/Odometry", "nav_msgs/Odometry", ", exclude: ['pose.covariance']"),
    ("tf2_msgs/TFMessage", "tf2_msgs/TFMessage", ""),
)


def generate(chains: int) -> str:
    lines = ["project: {name: Bench, middleware: ROS2, scheduler: LRU}", "accelerators:"]
    for index, (source, result, _) in enumerate(KINDS):
        for stage, (a, b) in enumerate(((source, source), (source, source), (source, result))):
            lines += [
                f"  - name: Kind{index}Stage{stage}",
                "    type: HLS",
                "    sources: ./accel.cpp",
                f"    interface: {{input: [{{message: {a}}}], output: [{{message: {b}}}]}}",
            ]
    lines.append("blocks:")
    for chain in range(chains):
        index = chain % len(KINDS)
        source, result, selection = KINDS[index]
        names = [f"C{chain}_sub", f"C{chain}_a", f"C{chain}_b", f"C{chain}_c", f"C{chain}_pub"]
        lines.append(
            f"  - {{name: {names[0]}, type: ROS>accelerator, message: {source}, "
            f"period: 1 ms, outgoing: [{{name: {names[1]}{selection}}}]}}"
        )
        for stage in range(3):
            lines.append(
                f"  - {{name: {names[stage + 1]}, type: Kind{index}Stage{stage}, "
                f"outgoing: [{{name: {names[stage + 2]}{selection}}}]}}"
            )
        lines.append(
            f"  - {{name: {names[4]}, type: accelerator>ROS, message: {result}, period: 1 ms}}"
        )
    return "\n".join(lines) + "\n"


def in_process(spec: Path) -> list[tuple[str, float]]:
    from rfc.passes.pipeline import PIPELINE
    from rfc.spec import load_spec

    start = time.perf_counter()
    design = load_spec(spec)
    phases = [("front-end", time.perf_counter() - start)]
    for step in PIPELINE:
        start = time.perf_counter()
        design = step.apply(design)
        phases.append((step.name, time.perf_counter() - start))
    return phases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chains", type=int, default=40)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        spec = Path(folder) / "bench.yaml"
        spec.write_text(generate(args.chains))
        (Path(folder) / "accel.cpp").write_text("// accelerator\n")
        runs = []
        for _ in range(args.repeat):
            start = time.perf_counter()
            result = subprocess.run(
                [sys.executable, "-m", "rfc", "check", str(spec)], capture_output=True, text=True
            )
            runs.append(time.perf_counter() - start)
            if result.returncode != 0:
                sys.exit(result.stderr)
        print(result.stdout.strip())
        median = statistics.median(runs)
        print(f"blocks              {5 * args.chains}")
        print(
            f"rfc check (median)  {median * 1000:8.0f} ms   target < {TARGET_S * 1000:.0f} ms"
            f"  ratio {median / TARGET_S:.2f}"
        )
        for name, seconds in in_process(spec):
            print(f"  {name:<24}{seconds * 1000:8.1f} ms (in process, first run)")


if __name__ == "__main__":
    main()
