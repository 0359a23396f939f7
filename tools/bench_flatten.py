"""Benchmark: flatten every message type of the ROS 1 noetic and ROS 2 humble stores.

Target (issue 2): under 1 s for both stores together, from definitions to layouts, with fresh
caches. Loading the stores themselves (rosbags' import and store construction) is reported apart.

Usage: .venv/bin/python tools/bench_flatten.py [--repeat N]
"""

from __future__ import annotations

import argparse
import statistics
import time

from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import MessageTypes, Middleware

STORES = ((Middleware.ROS1, "noetic"), (Middleware.ROS2, "humble"))


def run_once() -> tuple[float, float, int, int]:
    start = time.perf_counter()
    stores = [MessageTypes(middleware, distro) for middleware, distro in STORES]
    loaded = time.perf_counter()
    types = leaves = 0
    for store in stores:
        for name in store.names():
            leaves += len(flatten(store, name).fields)
            types += 1
    done = time.perf_counter()
    return loaded - start, done - loaded, types, leaves


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    runs = [run_once() for _ in range(args.repeat)]
    load = statistics.median(r[0] for r in runs)
    flat = statistics.median(r[1] for r in runs)
    _, _, types, leaves = runs[0]
    print(f"types flattened     {types} ({leaves} top-level leaves)")
    print(f"store load (median) {load * 1000:8.1f} ms")
    print(f"flatten    (median) {flat * 1000:8.1f} ms   target < 1000 ms  ratio {flat / 1.0:.3f}")


if __name__ == "__main__":
    main()
