"""`rfc build --estimate` cold and warm, and the timing it reports, for the example systems.

Cold: an empty module cache (every module of hw/verilog/ mapped by Yosys, two at a time, then
the paths across blocks timed); warm: the same build again, every figure from the cache. Prints
a Markdown table with each wall time and CPU time (the `rfc` process and its Yosys processes,
which the shared machine's load does not inflate), the load average while it ran, the anchor
(the figure before this flow), the target and the ratio of the figure to the target, then the
whole logic's critical path and Fmax from report.md.

A warm build converts no MyHDL either (the conversion cache): the benchmark checks that it
writes the cold build's files byte for byte. `--cache DIR` keeps both caches in DIR instead of
a fresh folder, so a second invocation measures warm builds only (its first row says "first").

Usage: python tools/bench_estimate.py [--systems quaternion franka] [--cache DIR]
"""

from __future__ import annotations

import argparse
import datetime
import os
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


@dataclass(frozen=True)
class System:
    """An example to estimate, with the figures it is measured against (seconds, None: none)."""

    spec: Path
    cold_anchor: float | None
    cold_target: float
    warm_anchor: float | None
    warm_target: float | None


QUATERNION = ROOT / "examples/quaternion_to_euler"
#: The anchors: `rfc build --estimate` before the boundary-logic flow, at a load of 12 to 14,
#: when the quaternion example shipped the iterative core (the pipelined one has none).
SYSTEMS = {
    "quaternion": System(QUATERNION / "project.yaml", None, 30, None, 3),
    "quaternion_iterative": System(QUATERNION / "project_iterative.yaml", 693, 30, 5.9, 3),
    "franka": System(ROOT / "examples/franka_fk/franka_fk.yaml", 1262, 120, 6.7, None),
}


@dataclass(frozen=True)
class Run:
    """One build: wall and CPU seconds, the load average at its end, its report."""

    wall: float
    cpu: float
    load: float
    report: str


def build(spec: Path, out: Path, cache: Path) -> Run:
    """Run one `rfc build --estimate` and measure it."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "rfc", "build", spec, "-o", out, "--estimate"],
        check=True,
        capture_output=True,
        cwd=ROOT,
        env={**os.environ, "RFC_CACHE_DIR": str(cache)},
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return Run(wall, cpu, os.getloadavg()[0], (out / "report.md").read_text())


def files(folder: Path) -> dict[Path, bytes]:
    """Every file a build wrote, by its path in the build."""
    return {p.relative_to(folder): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def whole_logic(report: str) -> str:
    """The whole logic's row of the report's Timing table: delay, levels, Fmax, path."""
    lines = report.split("## Timing")[1].splitlines()
    row = next(line for line in lines if line.startswith("| **") and "(whole logic)" in line)
    cells = [c.strip() for c in row.strip("|").split("|")]
    return f"{cells[1]} ns, {cells[2]} levels, {cells[3]} MHz: {cells[5]} ({cells[6]})"


def row(name: str, what: str, run: Run, anchor: float | None, target: float | None) -> str:
    """A table row: the figure against its anchor and target (ratio > 1: over the target).

    The ratio is given for the wall time and for the CPU time: on a loaded machine the wall
    time is mostly waiting, and the CPU time is what the build would take on idle cores.
    """
    ratio = (
        f"{run.wall / target:.2f} x the target ({run.cpu / target:.2f} x by CPU)" if target else "—"
    )
    goal = f"≤ {target:g} s" if target else "—"
    return (
        f"| {name} | {what} | {run.wall:.1f} s | {run.cpu:.1f} s | {run.load:.1f} | "
        f"{f'{anchor:g} s' if anchor else '—'} | {goal} | {ratio} | {datetime.date.today()} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--systems", nargs="+", default=list(SYSTEMS), choices=list(SYSTEMS))
    parser.add_argument("--cache", type=Path, help="keep the caches here (default: a fresh one)")
    args = parser.parse_args()
    print("| system | build | wall | CPU | load | anchor | target | ratio | date |")
    print("|---|---|---:|---:|---:|---:|---:|---|---|")
    paths = []
    for name in args.systems:
        system = SYSTEMS[name]
        with tempfile.TemporaryDirectory(prefix="rfc-bench-estimate-") as scratch:
            work = Path(scratch)
            cache = args.cache or work / "cache"
            fresh = not (cache.is_dir() and any(cache.iterdir()))
            cold = build(system.spec, work / "cold", cache)
            first = "cold" if fresh else "first"
            print(row(name, first, cold, system.cold_anchor, system.cold_target), flush=True)
            warm = build(system.spec, work / "warm", cache)
            print(row(name, "warm", warm, system.warm_anchor, system.warm_target), flush=True)
            assert files(work / "warm") == files(work / "cold"), "the warm build wrote other files"
        paths.append(f"- {name}: {whole_logic(cold.report)}")
    print("\nWhole logic (cell delay, levels, Fmax, path):", *paths, sep="\n")


if __name__ == "__main__":
    main()
