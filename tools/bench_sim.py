"""rfc sim's marginal cost per message on each simulator, for the quaternion system.

Replays two bags of random orientations (SMALL and LARGE messages, 1.5 µs apart) through
`rfc sim --simulator S` and reports (t_large - t_small) / (LARGE - SMALL): the cost of one more
message, without process start, spec compilation, logic generation and model compilation (a
warm-up run fills Verilator's model cache first). Prints a Markdown table.

Usage: python tools/bench_sim.py [--small 20] [--large 220] [--simulators ghdl verilator]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rfc.messages.rosbags_adapter import message_types, write_bag  # noqa: E402

SPEC = ROOT / "examples/quaternion_to_euler/project.yaml"
QUATERNION = "geometry_msgs/msg/Quaternion"


def orientations_bag(path: Path, count: int) -> None:
    types = message_types("ros2")
    rng = np.random.default_rng(count)
    quaternions = rng.normal(size=(count, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    messages = [
        (
            "/imu/orientation",
            1500 * (i + 1),
            types.serialize(
                types.build(QUATERNION, dict(zip("xyzw", map(float, q), strict=True))), QUATERNION
            ),
        )
        for i, q in enumerate(quaternions)
    ]
    write_bag(path, types, {"/imu/orientation": QUATERNION}, messages)


def replay(bag: Path, out: Path, simulator: str) -> float:
    start = time.perf_counter()
    options = ["--json", "--drain-cycles", "300", "--simulator", simulator]
    subprocess.run(
        [sys.executable, "-m", "rfc", "sim", SPEC, "--bag", bag, "--out", out, *options],
        check=True,
        capture_output=True,
        cwd=ROOT,
    )
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--small", type=int, default=20)
    parser.add_argument("--large", type=int, default=220)
    parser.add_argument("--simulators", nargs="+", default=["ghdl", "verilator"])
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="rfc-bench-sim-") as scratch:
        folder = Path(scratch)
        bags = {n: folder / f"q{n}.mcap" for n in (args.small, args.large)}
        for count, bag in bags.items():
            orientations_bag(bag, count)
        for simulator in args.simulators:
            replay(bags[args.small], folder / "warm.mcap", simulator)  # caches, page cache
            times = {n: replay(bag, folder / f"{n}.mcap", simulator) for n, bag in bags.items()}
            marginal = (times[args.large] - times[args.small]) / (args.large - args.small)
            rows.append((simulator, times[args.small], times[args.large], marginal))
    print(f"| simulator | {args.small} messages | {args.large} messages | per message |")
    print("|---|---:|---:|---:|")
    for simulator, small, large, marginal in rows:
        print(f"| {simulator} | {small:.1f} s | {large:.1f} s | {1000 * marginal:.2f} ms |")


if __name__ == "__main__":
    main()
