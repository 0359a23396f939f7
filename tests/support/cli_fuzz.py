"""Random bad input for the command line: mutated specs, random bytes, random option values.

Shared by the bounded property test (tests/cli/test_fuzz.py) and the longer campaign
(tools/fuzz_cli.py). Every case runs the real entry point, `rfc.cli.main`, in process, or the
real `rfc` in a subprocess where a fresh interpreter matters (builds); a case is
handled when rfc exits 0, 1 (one `error:` message) or 2 (bad usage) without an exception
escaping, within its time limit, and when a build it accepted holds VHDL that GHDL analyses.
"""

from __future__ import annotations

import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from hypothesis import strategies as st

from rfc.cli import main
from rfc.toolchain.ghdl import GhdlError, analyze
from rfc.user_code import TIME_LIMIT_ENV

ROOT = Path(__file__).resolve().parents[2]
LISTING_1 = ROOT / "examples" / "rotation_converter"
SEEDS = {
    "yaml": (LISTING_1 / "RotationConverterNode.yaml").read_text(),
    "py": (LISTING_1 / "RotationConverterNode.py").read_text(),
}
#: Seconds a case may take (rfc's own work; user code has the 2 s limit set below).
CASE_LIMIT_S = 60.0
#: Values that broke rfc once, or sit on an edge: names, numbers, paths, text.
NASTY = (
    "",
    "0",
    "-1",
    "inf",
    ".inf",
    ".nan",
    "1e300",
    "Class",
    "Def",
    "rst",
    "aclk",
    "RotationConverterNode_manager",
    "signal",
    "Q" * 1100,
    "x" * 65,
    "null",
    "[]",
    "{}",
    "'",
    '"',
    ":",
    "- a",
    "xc7z020",
    "xc7z020clg400-9",
    "./missing.cpp",
    "/dev/zero",
    "ROS2",
    "geometry_msgs/Pose",
    "ref.py:nothing",
    "é",
    "\t",
    "import sys; sys.exit(0)",
    "while True: pass",
    "raise SystemExit",
)


@dataclass(frozen=True)
class Outcome:
    """How one run of the command line ended."""

    args: tuple[str, ...]
    status: int | None
    stderr: str
    seconds: float
    escaped: str | None
    """The exception that escaped `main` (a traceback for a user), or None."""

    @property
    def handled(self) -> bool:
        """Exit 0, 1 with one error message, or 2, in time, and nothing escaped."""
        if self.escaped is not None or self.seconds > CASE_LIMIT_S:
            return False
        if self.status == 1:
            return self.stderr.startswith("error: ") and "Traceback" not in self.stderr
        return self.status in (0, 2)


def run(args: list[str], cwd: Path, fresh: bool = False) -> Outcome:
    """Run `rfc ARGS` from `cwd` (user code limited to 2 s), in process or `fresh`.

    A fresh interpreter (a subprocess, as a user runs rfc) is needed for builds: MyHDL keeps
    elaboration state between conversions, so one failed in-process build can disturb the next.
    """
    if fresh:
        return _run_fresh(args, cwd)
    started = time.monotonic()
    stderr = io.StringIO()
    status: int | None = 0
    escaped = None
    saved = (sys.argv, os.getcwd(), os.environ.get(TIME_LIMIT_ENV))
    sys.argv = ["rfc", *args]
    os.chdir(cwd)
    os.environ[TIME_LIMIT_ENV] = "2"
    try:
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            main()
    except SystemExit as exc:
        status = 0 if exc.code is None else exc.code if isinstance(exc.code, int) else 1
    except BaseException as exc:  # exactly what the fuzzing looks for
        escaped = f"{type(exc).__name__}: {exc}"
    finally:
        sys.argv = saved[0]
        os.chdir(saved[1])
        if saved[2] is None:
            os.environ.pop(TIME_LIMIT_ENV, None)
        else:
            os.environ[TIME_LIMIT_ENV] = saved[2]
    return Outcome(tuple(args), status, stderr.getvalue(), time.monotonic() - started, escaped)


def _run_fresh(args: list[str], cwd: Path) -> Outcome:
    started = time.monotonic()
    try:
        done = subprocess.run(
            [sys.executable, "-m", "rfc", *args],
            cwd=cwd,
            capture_output=True,
            text=True,
            env={**os.environ, TIME_LIMIT_ENV: "2"},
            timeout=CASE_LIMIT_S,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return Outcome(tuple(args), None, "", time.monotonic() - started, "no end in time")
    stderr = done.stderr
    escaped = stderr.strip().splitlines()[-1] if "Traceback" in stderr else None
    return Outcome(tuple(args), done.returncode, stderr, time.monotonic() - started, escaped)


@st.composite
def mutated_spec(draw: st.DrawFn) -> tuple[str, str]:
    """A seed spec (YAML or Python) with one to three lines changed, dropped, or doubled."""
    suffix = draw(st.sampled_from(sorted(SEEDS)))
    lines = SEEDS[suffix].splitlines()
    for _ in range(draw(st.integers(1, 3))):
        index = draw(st.integers(0, len(lines) - 1))
        action = draw(st.sampled_from(["value", "drop", "double", "insert"]))
        value = draw(st.one_of(st.sampled_from(NASTY), st.text(max_size=12)))
        if action == "value":
            head, colon, _ = lines[index].partition(":" if suffix == "yaml" else "(")
            lines[index] = f"{head}{colon} {value}" if colon else value
        elif action == "drop":
            del lines[index]
            lines = lines or [""]
        elif action == "double":
            lines.insert(index, lines[index])
        else:
            lines.insert(index, value)
    return suffix, "\n".join(lines) + "\n"


def listing_1_copy(directory: Path) -> None:
    """Listing 1's files in `directory` (the seeds refer to the HLS source beside them)."""
    for path in LISTING_1.iterdir():
        shutil.copy(path, directory / path.name)


def build_analyses(output: Path) -> str | None:
    """GHDL's complaint about an accepted build's VHDL (hw/files.txt, in order), or None."""
    listing = output / "hw" / "files.txt"
    if not listing.is_file():
        return None  # a build without logic
    files = [output / "hw" / name for name in listing.read_text().split()]
    with tempfile.TemporaryDirectory(prefix="rfc-fuzz-ghdl-") as work:
        try:
            analyze(files, Path(work))
        except GhdlError as exc:
            return str(exc)
    return None
