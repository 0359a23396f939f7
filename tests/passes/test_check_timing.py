"""check-timing: `rfc check` names the rfc.lib blocks of a MyHDL accelerator too slow for the clock.

The quaternion example's two cores against the measured table (lib/arith/timing.json): at
100 MHz every block of both meets the clock (the iterative core's CORDIC splits each
micro-rotation over two cycles), so nothing is said; just above the slowest block's estimate
each block that misses is named, with a faster variant; at a clock every block meets, nothing
is said.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from rfc.lib.arith.timing import blocks_in, measured_timing, suggestion
from rfc.toolchain import elaboration
from rfc.toolchain.sta import ROUTING_FACTOR
from tests.examples.quaternion_to_euler.example import core_arguments, core_ports, cores
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "quaternion_to_euler"
WARNING = re.compile(
    r"^warning: (?P<where>\S+): accelerator 'QuaternionToEuler' uses (?P<key>.+), estimated at "
    r"(?P<fmax>\d+) MHz \((?P<delay>[\d.]+) ns of cells, period 2x that\), below the clock of "
    r"(?P<clock>[\d.]+) MHz; use (?P<instead>.+)$"
)


def core_blocks(name: str):
    """The known blocks of one quaternion core, as the pass finds them."""
    core = next(c for c in cores() if c.name == name)
    with elaboration():
        return blocks_in(core.block(*core_arguments(core_ports())))


def too_slow(name: str, clock_mhz: float) -> dict[str, float]:
    """Each block of a core the table says misses `clock_mhz`, with its estimated Fmax."""
    table = measured_timing()
    slow = {}
    for key in core_blocks(name):
        fmax = 1e6 / (table[key].delay_ps * ROUTING_FACTOR)
        if fmax < clock_mhz:
            slow[str(key)] = fmax
    return slow


def spec_at(tmp_path: Path, spec: str, clock_mhz: int) -> Path:
    """A copy of the example with `spec` at another clock."""
    folder = tmp_path / "example"
    shutil.copytree(EXAMPLE, folder, ignore=shutil.ignore_patterns("hls", "__pycache__"))
    path = folder / spec
    text = path.read_text()
    path.write_text(re.sub(r"clockMHz: \d+", f"clockMHz: {clock_mhz}", text))
    return path


def warnings_of(stderr: str) -> list[re.Match[str]]:
    lines = [line for line in stderr.splitlines() if line.startswith("warning:")]
    matches = [WARNING.match(line) for line in lines]
    assert all(matches), lines
    return matches  # type: ignore[return-value]


def test_the_table_covers_every_block_both_cores_use():
    for name in ("pipelined", "iterative"):
        assert set(core_blocks(name)) <= set(measured_timing())


def test_the_cores_name_the_blocks_they_instantiate():
    pipelined = {(k.block, k.variant) for k in core_blocks("pipelined")}
    iterative = {(k.block, k.variant) for k in core_blocks("iterative")}
    assert pipelined == {
        ("float_to_fixed", "pipelined"),
        ("exact_multiply", "pipelined"),
        ("cordic_vectoring", "pipelined"),
        ("fixed_to_float", "pipelined"),
    }
    assert iterative == {
        ("float_to_fixed", "pipelined"),
        ("exact_multiply", "pipelined"),
        ("cordic_vectoring", "iterative"),
        ("fixed_to_float", "pipelined"),
    }


def test_check_warns_about_each_block_of_the_iterative_core_that_misses_the_clock(tmp_path):
    table = measured_timing()
    slowest = max(table[k].delay_ps for k in core_blocks("iterative"))
    clock = int(1e6 / (slowest * ROUTING_FACTOR)) + 1  # MHz: the slowest block misses it
    expected = too_slow("iterative", clock)
    assert expected
    result = run_rfc("check", spec_at(tmp_path, "project_iterative.yaml", clock))
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("ok: ")
    found = warnings_of(result.stderr)
    assert {m["key"]: int(m["fmax"]) for m in found} == {k: round(v) for k, v in expected.items()}
    for match in found:
        assert match["where"].startswith(str(tmp_path / "example" / "project_iterative.yaml:"))
        assert float(match["clock"]) == clock
        key = next(k for k in core_blocks("iterative") if str(k) == match["key"])
        assert match["instead"] == suggestion(key)


def test_check_says_nothing_when_every_block_meets_the_clock(tmp_path):
    table = measured_timing()
    slowest = max(table[k].delay_ps for k in core_blocks("iterative"))
    clock = int(1e6 / (slowest * ROUTING_FACTOR))  # MHz, rounded down: every block meets it
    result = run_rfc("check", spec_at(tmp_path, "project_iterative.yaml", clock))
    assert result.returncode == 0, result.stderr
    assert not warnings_of(result.stderr)


@pytest.mark.parametrize("spec", ["project.yaml", "project_iterative.yaml"])
def test_the_build_warns_as_check_does(tmp_path, spec):
    check = run_rfc("check", spec, cwd=EXAMPLE)
    build = run_rfc("build", spec, "-o", tmp_path / "out", cwd=EXAMPLE)
    assert build.returncode == 0, build.stderr
    assert [m.group(0) for m in warnings_of(build.stderr)] == [
        m.group(0) for m in warnings_of(check.stderr)
    ]


@pytest.mark.parametrize(("spec", "core"), [("project.yaml", "pipelined"),
                                            ("project_iterative.yaml", "iterative")])  # fmt: skip
def test_both_cores_meet_100_mhz_block_by_block(spec, core):
    assert too_slow(core, 100) == {}
    result = run_rfc("check", spec, cwd=EXAMPLE)
    assert result.returncode == 0, result.stderr
    assert not warnings_of(result.stderr)
