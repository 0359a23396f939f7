"""Where a cold `rfc build --estimate` spends its CPU, module by module, pass by pass.

Builds a spec without `--estimate`, then runs on each module of its hw/verilog/ the Yosys
script `module_estimate` runs (`rfc.toolchain.yosys.estimate_script`), one process at a time
with `yosys -d`, and prints a Markdown table: the module's Verilog size, the CPU time and peak
memory of its Yosys process (the CPU time includes ABC's), and the passes that took the
most. The shared machine's load inflates wall times only, so none is printed.

Usage: python tools/profile_estimate.py SPEC [--modules NAME ...] [--passes N]
"""

from __future__ import annotations

import argparse
import re
import resource
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from rfc.toolchain import module_instances
from rfc.toolchain.yosys import estimate_script

#: A line of `yosys -d`'s summary: ``   35%     1 calls   22.920 sec abc9_exe``.
_PASS = re.compile(r"^\s*\d+%\s+(\d+) calls\s+([\d.]+) sec (\S+)$", re.M)


@dataclass(frozen=True)
class Profile:
    """One module's mapping: CPU seconds (Yosys and ABC), Yosys' peak memory, its passes."""

    cpu: float
    peak_mb: float
    passes: tuple[tuple[str, int, float], ...]  # (pass, calls, seconds), the longest first
    failed: bool


def profile(verilog: Path, top: str, work: Path, submodules: list[Path]) -> Profile:
    """Run `estimate_script` on `top` with `yosys -d` and read its statistics."""
    executable = shutil.which("yosys")
    if executable is None:
        sys.exit("yosys is not installed; run tools/setup.sh")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run(
        [executable, "-d", "-p", estimate_script(verilog, top, work, submodules)],
        capture_output=True,
        text=True,
        check=False,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    passes = sorted(
        ((name, int(calls), float(seconds)) for calls, seconds, name in _PASS.findall(run.stdout)),
        key=lambda p: p[2],
        reverse=True,
    )
    peak = re.search(r"MEM: ([\d.]+) MB peak", run.stdout)
    return Profile(cpu, float(peak.group(1)) if peak else 0.0, tuple(passes), run.returncode != 0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("spec", type=Path)
    parser.add_argument("--modules", nargs="+", help="only these modules (default: every one)")
    parser.add_argument("--passes", type=int, default=5, help="passes listed per module")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="rfc-profile-estimate-") as scratch:
        out = Path(scratch) / "build"
        subprocess.run(
            [sys.executable, "-m", "rfc", "build", args.spec, "-o", out],
            check=True,
            capture_output=True,
        )
        files = sorted((out / "hw/verilog").glob("*.v"), key=lambda f: -f.stat().st_size)
        names = {f.stem: f for f in files}
        print("| module | Verilog | Yosys CPU | peak memory | longest passes (calls) |")
        print("|---|---:|---:|---:|---|")
        for verilog in files:
            if args.modules and verilog.stem not in args.modules:
                continue
            work = Path(scratch) / verilog.stem
            work.mkdir()
            inside = module_instances(verilog.read_text(), names)  # mapped as black boxes
            submodules = [names[m] for m in dict.fromkeys(m for _, m in inside)]
            run = profile(verilog, verilog.stem, work, submodules)
            longest = ", ".join(
                f"`{name}` {seconds:.1f} s ({calls})"
                for name, calls, seconds in run.passes[: args.passes]
            )
            if run.failed:
                longest = "Yosys failed (abc9 and a block RAM: `module_estimate` maps it twice)"
            print(
                f"| {verilog.stem} | {verilog.stat().st_size / 1000:.1f} KB | {run.cpu:.1f} s | "
                f"{run.peak_mb:.0f} MB | {longest} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
