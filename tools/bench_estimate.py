"""`rfc build --estimate` cold and warm, and the timing it reports, for the example systems.

Cold: an empty module cache (every module of hw/verilog/ mapped by Yosys, two at a time, then
the whole logic timed); warm: the same build again, every figure from the cache. Prints a
Markdown table with the wall times against their targets and the whole logic's critical
path and Fmax from report.md.

Usage: python tools/bench_estimate.py [--systems quaternion franka]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: name → (spec, cold target in seconds, warm target in seconds); None where none was set.
SYSTEMS = {
    "quaternion": (ROOT / "examples/quaternion_to_euler/project.yaml", 30.0, 3.0),
    "franka": (ROOT / "examples/franka_fk/franka_fk.yaml", 120.0, None),
}


def build(spec: Path, out: Path, cache: Path) -> tuple[float, str]:
    """Wall time of one `rfc build --estimate`, and its report."""
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "rfc", "build", spec, "-o", out, "--estimate"],
        check=True,
        capture_output=True,
        cwd=ROOT,
        env={**os.environ, "RFC_CACHE_DIR": str(cache)},
    )
    return time.perf_counter() - start, (out / "report.md").read_text()


def whole_logic(report: str) -> str:
    """The whole logic's row of the report's Timing table: delay, levels, Fmax, path."""
    lines = report.split("## Timing")[1].splitlines()
    row = next(line for line in lines if line.startswith("| **") and "(whole logic)" in line)
    cells = [c.strip() for c in row.strip("|").split("|")]
    return f"{cells[1]} ns, {cells[2]} levels, {cells[3]} MHz: {cells[5]} ({cells[6]})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--systems", nargs="+", default=list(SYSTEMS), choices=list(SYSTEMS))
    args = parser.parse_args()
    print("| system | cold | target | warm | target | whole logic (cell delay, Fmax, path) |")
    print("|---|---:|---:|---:|---:|---|")
    for name in args.systems:
        spec, cold_target, warm_target = SYSTEMS[name]
        with tempfile.TemporaryDirectory(prefix="rfc-bench-estimate-") as scratch:
            work = Path(scratch)
            cold, report = build(spec, work / "cold", work / "cache")
            warm, again = build(spec, work / "warm", work / "cache")
        assert report == again, "the warm build reported other figures than the cold one"
        targets = [f"≤ {t:g} s" if t else "—" for t in (cold_target, warm_target)]
        print(
            f"| {name} | {cold:.1f} s | {targets[0]} | {warm:.1f} s | {targets[1]} "
            f"| {whole_logic(report)} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
