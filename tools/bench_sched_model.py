"""Benchmark: scheduler-cycles per second of the vectorized models (one core).

A scheduler-cycle is one clock cycle of one replicate. The DSE (issue 6) needs about 1e8 per
minute on 2 cores for its full sweep, i.e. about 8.3e5 per second per core ("ratio" column).
"vs SimSo" compares with the anchor (docs/architecture.md, Targets: EDF, N = 256, 50,000
cycles in 31 s) per replicate-cycle. Traffic comes from
`Publishers` (DSE-like: T ~ 100, F ~ 100, all released at cycle 0) and its cost is reported
apart from the scheduler's own `step`.

Usage: .venv/bin/python tools/bench_sched_model.py [--n 2 16 256] [--batch 1 100 1000]
       [--cycles 2000]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from rfc.lib.schedulers.model import make_model
from rfc.lib.schedulers.model.traffic import Publishers
from rfc.lib.schedulers.spec import Algorithm

TARGET_PER_CORE = 1e8 / 60 / 2
#: The anchor (docs/architecture.md, Targets): SimSo runs EDF, N = 256, 50,000 cycles in 31 s.
SIMSO_CYCLES_PER_SECOND = 50_000 / 31


def measure(algorithm: str, n: int, batch: int, cycles: int) -> tuple[float, float]:
    rng = np.random.default_rng(0)
    transfer = np.clip(np.rint(rng.normal(100, 50, size=(batch, n))), 1, None).astype(int)
    idle = np.clip(np.rint(rng.normal(100, 50, size=(batch, n))), 1, None).astype(int)
    model = make_model(algorithm, n, transfer, transfer + idle, batch=batch)
    publishers = Publishers(transfer, gap=idle)
    scheduler = traffic = 0.0
    for _ in range(cycles):
        start = time.perf_counter()
        grant = model.step(publishers.request, publishers.last)
        middle = time.perf_counter()
        publishers.advance(grant)
        traffic += time.perf_counter() - middle
        scheduler += middle - start
    return batch * cycles / scheduler, batch * cycles / (scheduler + traffic)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[2, 16, 256])
    parser.add_argument("--batch", type=int, nargs="+", default=[1, 100, 1000])
    parser.add_argument("--cycles", type=int, default=2000)
    args = parser.parse_args()
    print(f"target: {TARGET_PER_CORE:.3g} scheduler-cycles/s per core")
    print(
        f"{'algorithm':9} {'N':>4} {'R':>5} {'step only':>12} {'with traffic':>13} "
        f"{'ratio':>6} {'vs SimSo':>9}"
    )
    for algorithm in Algorithm:
        for n in args.n:
            for batch in args.batch:
                alone, loaded = measure(algorithm.value, n, batch, args.cycles)
                print(
                    f"{algorithm.value:9} {n:4} {batch:5} {alone:12.3g} {loaded:13.3g} "
                    f"{loaded / TARGET_PER_CORE:6.2f} {loaded / SIMSO_CYCLES_PER_SECOND:8.0f}x",
                    flush=True,
                )


if __name__ == "__main__":
    main()
