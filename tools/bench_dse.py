"""Benchmark: the DSE's full paper sweep and the SimSo point (docs/architecture.md, Targets).

Measures, each apart:

* compile time of the numba kernels in a fresh process with an empty cache, and the time the
  same process takes when the kernels load from numba's on-disk cache (what `rfc dse` pays);
* the SimSo point: EDF (LOEDF and ROEDF), N = 256, 50,000 cycles, one replicate, warm kernels,
  best of `--repeat` runs, as a ratio to SimSo's 31 s (target: at least 100x);
* the SimSo point end to end as a user runs it: `rfc dse --n 256 --dataset cc4 --replicates 2
  --no-synth` in a new process (start, kernels from the cache, the six schedulers and Figure 14's
  combinations, tables, report; figures are drawn only with `--figures`), on one process and on
  `--jobs`, as a ratio to SimSo's 31 s per run times the six schedulers' two replicates (372 s;
  target: at least 100x);
* the full paper sweep: six schedulers x N in 2..256 on the large dataset (200 replicates of
  10,000 cycles) and the four corner cases (10 replicates of 50,000 cycles), plus Figure 14's
  combinations, on `--jobs` processes (target: 60 s on 2 cores); simulation only, LUT/FF come
  from the cached synthesis and are not part of the figure;
* peak resident memory of the sweep: the parent's plus `--jobs` times the largest worker's.

The load average is printed with the figures, and the sweep's CPU time (parent and workers) with
the wall time it would take on idle cores: the machine may be shared.
With `--output DIR` the sweep's tables, figures and report are written there (docs/dse is made
this way), with LUT/FF read from `--resources CSV` (the scheduler synthesis sweep's
docs/schedulers/resources.csv) instead of synthesizing again.

Usage: .venv/bin/python tools/bench_dse.py [--jobs 2] [--repeat 3] [--skip-sweep]
       [--only-end-to-end] [--output DIR --resources CSV]
"""

from __future__ import annotations

import argparse
import csv
import os
import resource
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

#: The anchor (docs/architecture.md, Targets): SimSo runs EDF, N = 256, 50,000 cycles in 31 s.
SIMSO_SECONDS = 31.0
SIMSO_N, SIMSO_CYCLES = 256, 50_000
SWEEP_TARGET_SECONDS = 60.0
MEMORY_LIMIT_MIB = 2048

#: Run in a fresh process: simulate every kernel once (compiles or loads them), timed.
_FIRST_RUN = textwrap.dedent(
    """
    import time
    start = time.perf_counter()
    from rfc.dse.datasets import DATASETS, draw
    from rfc.dse.engine import simulate
    from rfc.dse.sweep import ALGORITHMS, COMBINATIONS
    imported = time.perf_counter()
    traffic = draw(DATASETS["cc1"], 4, 1)
    for scheduler in (*ALGORITHMS, *COMBINATIONS):
        simulate(scheduler, traffic, 100)
    print(imported - start, time.perf_counter() - imported)
    """
)


def first_run(cache: Path) -> tuple[float, float]:
    """(import seconds, first-simulation seconds) of a new process with numba cache `cache`."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    done = subprocess.run(
        [sys.executable, "-c", _FIRST_RUN], env=env, capture_output=True, text=True, check=True
    )
    imported, simulated = (float(v) for v in done.stdout.split())
    return imported, simulated


def compile_times() -> None:
    """Kernels compiled into an empty cache, then loaded from it by a second process."""
    with tempfile.TemporaryDirectory(prefix="rfc-numba-") as cache:
        _, cold = first_run(Path(cache))
        _, warm = first_run(Path(cache))
    print(f"kernels, first run in a new process: compile {cold:.1f} s; from the cache {warm:.2f} s")


def simso_point(repeat: int) -> None:
    """EDF at N = 256 for 50,000 cycles, one replicate (kernels already warm)."""
    from rfc.dse.datasets import DATASETS, draw
    from rfc.dse.engine import simulate

    traffic = draw(DATASETS["large"], SIMSO_N, 1)
    simulate("LOEDF", traffic, 100)  # load the kernels
    for scheduler in ("LOEDF", "ROEDF"):
        best = float("inf")
        for _ in range(repeat):
            start = time.perf_counter()
            simulate(scheduler, traffic, SIMSO_CYCLES)
            best = min(best, time.perf_counter() - start)
        print(
            f"SimSo point, {scheduler} N={SIMSO_N} {SIMSO_CYCLES} cycles x1: {best * 1e3:.1f} ms, "
            f"{SIMSO_SECONDS / best:.0f}x SimSo (target >= 100x)"
        )


def end_to_end(jobs: int, repeat: int) -> None:
    """`rfc dse` at the SimSo point in a new process, best of `repeat` (bench_startup's timing)."""
    from bench_startup import best

    anchor = SIMSO_SECONDS * 6 * 2  # six schedulers, two replicates, one SimSo run each
    with tempfile.TemporaryDirectory(prefix="rfc-dse-") as directory:
        for workers in sorted({1, jobs}):
            wall, cpu = best(
                repeat, "dse", "--n", str(SIMSO_N), "--dataset", "cc4", "--replicates", "2",
                "--no-synth", "--jobs", str(workers), "-o", str(Path(directory) / "out"), "--json",
            )  # fmt: skip
            print(
                f"rfc dse at the SimSo point, --jobs {workers}, end to end: {wall:.2f} s wall, "
                f"{cpu:.2f} s CPU: {anchor / wall:.0f}x SimSo's {anchor:.0f} s by wall, "
                f"{anchor / cpu:.0f}x by CPU (target >= 100x)"
            )


def _cpu_seconds() -> float:
    """User + system time of this process and its finished children."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _resources(path: Path):
    from rfc.dse.sweep import Resources

    with path.open() as rows:
        return tuple(
            Resources(row["algorithm"], int(row["n"]), int(row["lut"]), int(row["ff"]))
            for row in csv.DictReader(rows)
        )


def full_sweep(jobs: int, output: Path | None, resources: Path | None) -> None:
    """The paper's sweep on `jobs` processes: wall time, scheduler-cycles, peak memory."""
    from rfc.dse.sweep import Plan, SweepResult, run_sweep

    plan = Plan()
    load = os.getloadavg()[0]
    cpu_before = _cpu_seconds()
    start = time.perf_counter()
    result = run_sweep(plan, jobs, synthesis=False)
    seconds = time.perf_counter() - start
    cpu = _cpu_seconds() - cpu_before
    cycles = sum(point.replicates * point.cycles for point in result.points)
    parent = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    worker = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    peak = parent + jobs * worker
    print(
        f"full sweep: {len(result.points)} points, {cycles / 1e6:.0f}e6 scheduler-cycles on "
        f"{jobs} processes in {seconds:.1f} s (target <= {SWEEP_TARGET_SECONDS:.0f} s), "
        f"{cycles / seconds / 1e6:.1f}e6 cycles/s; load average at start {load:.1f}"
    )
    print(
        f"CPU time of the sweep: {cpu:.1f} s, i.e. {cpu / jobs:.1f} s on {jobs} idle cores "
        f"({cycles / cpu / 1e6:.1f}e6 scheduler-cycles per CPU-second)"
    )
    print(
        f"peak memory: parent {parent:.0f} MiB + {jobs} x worker {worker:.0f} MiB = "
        f"{peak:.0f} MiB (limit {MEMORY_LIMIT_MIB} MiB)"
    )
    if output is not None:
        from rfc.dse.output import write_sweep

        measured = _resources(resources) if resources else ()
        write_sweep(SweepResult(plan, result.points, measured), (), output, figures=True)
        print(f"wrote the sweep's tables, figures and report into {output}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--skip-sweep", action="store_true")
    parser.add_argument("--only-end-to-end", action="store_true")
    parser.add_argument("--output", type=Path)
    parser.add_argument("--resources", type=Path)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    end_to_end(args.jobs, args.repeat)
    if args.only_end_to_end:
        return
    compile_times()
    simso_point(args.repeat)
    if not args.skip_sweep:
        full_sweep(args.jobs, args.output, args.resources)


if __name__ == "__main__":
    main()
