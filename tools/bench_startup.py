"""Benchmark: start-up of the command line, measured as a user runs it (process start included).

Times `rfc --help` (target: at most 0.3 s, docs/architecture.md, Targets) and `rfc check` of the
quaternion example, each the best of `--repeat` runs in a new process, wall and CPU time (user +
system of the process). The machine may be shared: the load average is printed, and the CPU time
is the figure that does not depend on it.

Usage: .venv/bin/python tools/bench_startup.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HELP_TARGET_SECONDS = 0.3


def timed(*args: str, cwd: Path = ROOT) -> tuple[float, float]:
    """(wall, CPU) seconds of one `rfc ARGS` in a new process, which must succeed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(
        [str(Path(sys.executable).parent / "rfc"), *args],
        cwd=cwd,
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def best(repeat: int, *args: str, cwd: Path = ROOT) -> tuple[float, float]:
    """The smallest wall and the smallest CPU time of `repeat` runs."""
    runs = [timed(*args, cwd=cwd) for _ in range(repeat)]
    return min(w for w, _ in runs), min(c for _, c in runs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    wall, cpu = best(args.repeat, "--help")
    print(
        f"rfc --help: {wall:.2f} s wall, {cpu:.2f} s CPU; target <= {HELP_TARGET_SECONDS} s: "
        f"{HELP_TARGET_SECONDS / wall:.2f}x the target's speed by wall, "
        f"{HELP_TARGET_SECONDS / cpu:.2f}x by CPU"
    )
    spec = "examples/quaternion_to_euler/project.yaml"
    wall, cpu = best(args.repeat, "check", spec)
    print(f"rfc check {spec}: {wall:.2f} s wall, {cpu:.2f} s CPU")


if __name__ == "__main__":
    main()
