"""Fuzzing campaign of the command line: the property test's cases, many more of them.

Runs mutated specs through `rfc check` and `rfc build` (GHDL analyses every accepted build),
random bytes as specs, sources and bags, and random option values, in process, and counts the
cases that were handled (exit 0/1/2 with one message, no exception escaping, in time, VHDL that
analyses). Prints a Markdown table for docs/robustness.md and the first unhandled cases.

Usage: .venv/bin/python tools/fuzz_cli.py [--cases N] [--builds N] [--seed S]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path

from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the shared case generators live under tests/support

from tests.support.cli_fuzz import (  # noqa: E402
    Outcome,
    build_analyses,
    listing_1_copy,
    mutated_spec,
    run,
)

tried: Counter[str] = Counter()
handled: Counter[str] = Counter()
failures: list[str] = []


def record(kind: str, outcome: Outcome, broken_vhdl: str | None = None) -> None:
    tried[kind] += 1
    if outcome.handled and broken_vhdl is None:
        handled[kind] += 1
    elif len(failures) < 20:
        failures.append(
            f"{kind}: rfc {' '.join(a[:60] for a in outcome.args)} -> status {outcome.status}, "
            f"{outcome.escaped or broken_vhdl or outcome.stderr[:300]!r}"
        )


def in_copy(work: Callable[[Path], None]) -> None:
    with tempfile.TemporaryDirectory() as directory:
        listing_1_copy(Path(directory))
        work(Path(directory))


def campaign(cases: int, builds: int, random_seed: int) -> None:
    options = settings(
        max_examples=cases, database=None, deadline=None, suppress_health_check=list(HealthCheck)
    )

    @seed(random_seed)
    @options
    @given(mutated_spec())
    def checks(case: tuple[str, str]) -> None:
        def work(directory: Path) -> None:
            (directory / f"spec.{case[0]}").write_text(case[1])
            record("mutated spec, rfc check", run(["check", f"spec.{case[0]}"], directory))

        in_copy(work)

    @seed(random_seed)
    @settings(options, max_examples=builds)
    @given(mutated_spec())
    def builds_(case: tuple[str, str]) -> None:
        def work(directory: Path) -> None:
            (directory / f"spec.{case[0]}").write_text(case[1])
            outcome = run(["build", f"spec.{case[0]}", "-o", "out"], directory, fresh=True)
            broken = build_analyses(directory / "out") if outcome.status == 0 else None
            record("mutated spec, rfc build", outcome, broken)
            if outcome.status == 0:
                record("… of which built, VHDL analysed by GHDL", outcome, broken)

        in_copy(work)

    @seed(random_seed)
    @options
    @given(st.binary(max_size=4096), st.sampled_from(["spec", "bag"]))
    def binaries(data: bytes, role: str) -> None:
        def work(directory: Path) -> None:
            for name in ("x.yaml", "x.bag"):
                (directory / name).write_bytes(data)
            args = {
                "spec": ["check", "x.yaml"],
                "bag": ["sim", "RotationConverterNode.yaml", "--bag", "x.bag", "--out", "o.bag"],
            }[role]
            record(f"random bytes as a {role}", run(args, directory))

        in_copy(work)

    @seed(random_seed)
    @settings(options, max_examples=builds)
    @given(st.binary(max_size=4096))
    def sources(data: bytes) -> None:
        def work(directory: Path) -> None:
            (directory / "QuaternionToEulerConverter.cpp").write_bytes(data)
            args = ["build", "RotationConverterNode.yaml", "-o", "out"]
            record("random bytes as a source, rfc build", run(args, directory, fresh=True))

        in_copy(work)

    @seed(random_seed)
    @options
    @given(
        st.sampled_from(["--depth", "--drain-cycles", "--stall-cycles", "--seed", "--queue"]),
        st.one_of(st.integers(-(2**70), 2**70).map(str), st.text(max_size=8)),
    )
    def option_values(option: str, value: str) -> None:
        def work(directory: Path) -> None:
            args = ["sim", "RotationConverterNode.yaml", "--bag", "x.bag", "--out", "o.bag"]
            record("random rfc sim option values", run([*args, option, value], directory))

        in_copy(work)

    for test in (checks, builds_, binaries, sources, option_values):
        test()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=1000, help="cases per kind (not builds)")
    parser.add_argument(
        "--builds",
        type=int,
        default=60,
        help="builds (subprocesses) of each kind: mutated specs, random bytes as a source",
    )
    parser.add_argument("--seed", type=int, default=1)
    arguments = parser.parse_args()
    started = time.monotonic()
    campaign(arguments.cases, arguments.builds, arguments.seed)
    minutes = (time.monotonic() - started) / 60
    print(f"| cases | tried | handled |  (seed {arguments.seed}, {minutes:.1f} min)")
    print("|---|---:|---:|")
    for kind in tried:
        print(f"| {kind} | {tried[kind]:,} | {handled[kind]:,} |")
    whole = [kind for kind in tried if not kind.startswith("…")]
    total, fine = sum(tried[k] for k in whole), sum(handled[k] for k in whole)
    print(f"| **all** | **{total:,}** | **{fine:,}** |")
    for failure in failures:
        print(failure)
    sys.exit(0 if tried == handled else 1)


if __name__ == "__main__":
    main()
