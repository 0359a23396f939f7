"""`rfc build --estimate`: resources and timing of every module and of the whole logic."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.lower.system.systems import PASS_THROUGH, point_system, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]


def build(folder: Path, clock_mhz: float, cache: Path):
    text = point_system("MyHDL", "pass.py", "pass_through")
    text = text.replace("scheduler: PFP}", f"scheduler: PFP, clockMHz: {clock_mhz}}}")
    spec = write_spec(folder, text, pass__py=PASS_THROUGH)
    out = folder / "build"
    env = {"RFC_CACHE_DIR": str(cache)}
    return run_rfc("build", spec, "-o", out, "--estimate", cwd=ROOT, env=env), out


def timing_rows(report: str) -> dict[str, list[str]]:
    section = report.split("## Timing")[1]
    rows = [line.split(" | ") for line in section.splitlines() if line.startswith("| `")]
    rows += [line.split(" | ") for line in section.splitlines() if line.startswith("| **")]
    return {row[0].strip("| *`").split("**")[0]: row[1:] for row in rows}


@pytest.mark.slow
def test_a_clock_the_logic_cannot_meet_is_a_warning_naming_the_path(tmp_path, synthesis_cache):
    result, out = build(tmp_path, 1000, synthesis_cache)
    assert result.returncode == 0, result.stderr
    warning = re.search(
        r"warning: the logic's estimated Fmax is (\d+) MHz, below its clock of 1000 MHz: "
        r"critical path (\S+) → (\S+) \(([\d.]+) ns of cells over (\d+) levels",
        result.stderr,
    )
    assert warning, result.stderr
    fmax, start, end, delay, _ = warning.groups()
    # the Fmax allows as long again for routing as the cells take
    assert int(fmax) == round(1000 / (2 * float(delay)))
    report = (out / "report.md").read_text()
    rows = timing_rows(report)
    whole = rows["point_system_pl"]
    assert whole[2].strip() == fmax
    assert whole[3].strip() == "**no**"
    assert f"`{start}` → `{end}`" in whole[4]
    # every module has its own path, none longer than the whole logic's
    modules = [n for n in rows if n != "point_system_pl"]
    assert {"point_sub_subscriber", "point_pub_publisher", "passpoint"} <= set(modules)
    timed = [name for name in modules if rows[name][0].strip() != "—"]
    assert {"point_sub_subscriber", "point_pub_publisher"} <= set(timed)  # the pass-through: wires
    for name in timed:
        assert float(rows[name][0]) <= float(delay), name
    assert "**Warning**: the logic's estimated Fmax" in report


@pytest.mark.slow
def test_a_clock_the_logic_meets_gives_no_warning(tmp_path, synthesis_cache):
    result, out = build(tmp_path, 5, synthesis_cache)
    assert result.returncode == 0, result.stderr
    assert "warning" not in result.stderr
    rows = timing_rows((out / "report.md").read_text())
    assert rows["point_system_pl"][3].strip() == "yes"
    assert "## Resources" in (out / "report.md").read_text()
