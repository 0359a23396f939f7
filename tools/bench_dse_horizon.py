"""Benchmark: `rfc dse SPEC` on a task set with long periods (the horizon follows the periods).

The sensor hub (examples/sensor_hub) with its six publishers' periods set to 25-33 ms at
100 MHz: the default horizon is then ten periods of the slowest publisher (33 M cycles), and
each of the ten candidates is simulated cycle by cycle over it. Prints the horizon, the
messages per publisher, the recommendation and the wall/CPU time of the whole command (process
start and warm numba kernels included; run once before to fill numba's cache), with the load
average: the machine may be shared.

Usage: .venv/bin/python tools/bench_dse_horizon.py [--horizon CYCLES]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HUB = ROOT / "examples" / "sensor_hub"
PERIODS = {
    "period: 2 us}": "period: 25 ms}",
    "period: 4 us}": "period: 33 ms}",
    "period: 500 ns, deadline: 300 ns}": "period: 28 ms}",
    "period: 500 ns, deadline: 200 ns}": "period: 30 ms}",
    "period: 1 us, deadline: 250 ns}": "period: 26 ms}",
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--horizon", type=int, default=None)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch) / "hub"
        shutil.copytree(HUB, folder)
        spec = folder / "SensorHub.yaml"
        text = spec.read_text()
        for old, new in PERIODS.items():
            text = text.replace(old, new)
        spec.write_text(text)
        command = [sys.executable, "-m", "rfc", "dse", str(spec), "--json"]
        command += ["--horizon", str(args.horizon)] if args.horizon else []
        start = time.perf_counter()
        done = subprocess.run(command, capture_output=True, text=True, check=True)
        wall = time.perf_counter() - start
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    document = json.loads(done.stdout)
    print(f"load average {os.getloadavg()[0]:.1f}")
    print(f"horizon {document['cycles']:,} cycles")
    print("messages per publisher", [p["messages"] for p in document["publishers"]])
    print(f"recommended {document['recommended']}")
    print(f"wall {wall:.1f} s, CPU {children.ru_utime + children.ru_stime:.1f} s")


if __name__ == "__main__":
    main()
