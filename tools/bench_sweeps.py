"""Benchmark: the scheduler resource sweep as independent jobs, serial against a Dask cluster.

Runs `rfc sched synth --algorithm A --n LIST --no-cache --json` (one GHDL + Yosys synthesis
per N) in a new process, once serially and once on a local Dask cluster of `--jobs` worker
processes (cluster start included), with an empty synthesis cache each time; prints the wall and
CPU times, the speed-up of the cluster over the serial run (its anchor) and whether the reports
are identical. The machine may be shared: the load average is printed with the figures.

Usage: .venv/bin/python tools/bench_sweeps.py [--algorithm LOEDF] [--n 4,8,16,32] [--jobs 2]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def timed_sweep(algorithm: str, sizes: str, jobs: int) -> tuple[float, float, list[dict]]:
    """(wall, CPU, reports) of one sweep in a new process with an empty synthesis cache."""
    with tempfile.TemporaryDirectory(prefix="rfc-bench-cache-") as cache:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run(
            [str(Path(sys.executable).parent / "rfc"), "sched", "synth", "-a", algorithm,
             "--n", sizes, "--no-cache", "--json", "--jobs", str(jobs)],
            env={**os.environ, "RFC_CACHE_DIR": cache}, capture_output=True, text=True, check=True,
        )  # fmt: skip
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(done.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--algorithm", default="LOEDF")
    parser.add_argument("--n", default="4,8,16,32")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    serial_wall, serial_cpu, serial = timed_sweep(args.algorithm, args.n, 1)
    print(f"rfc sched synth -a {args.algorithm} --n {args.n}, serial: {serial_wall:.1f} s wall, "
          f"{serial_cpu:.1f} s CPU")  # fmt: skip
    wall, cpu, clustered = timed_sweep(args.algorithm, args.n, args.jobs)
    print(
        f"same on a local Dask cluster of {args.jobs} workers: {wall:.1f} s wall, {cpu:.1f} s CPU "
        f"(workers included): {serial_wall / wall:.2f}x the serial run by wall; reports "
        f"{'identical' if clustered == serial else 'DIFFERENT'}"
    )


if __name__ == "__main__":
    main()
