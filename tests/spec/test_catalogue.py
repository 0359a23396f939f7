"""The catalogue of bad specs: each gives its pinned message, at its line, and writes nothing.

Every spec in catalogue/ (the YAML files and python_*.py; parts.py and accel.cpp are shared
valid parts) starts with two comment lines that pin what `rfc build` must print:
``# error: FILE:LINE:COL: message`` and ``# hint: text`` (or ``# hint: none``). The test runs
the real command line from the catalogue folder, as a user would.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from rfc.cli import main
from tests.support.cli import run_rfc

CATALOGUE = Path(__file__).parent / "catalogue"
CASES = sorted([*CATALOGUE.glob("*.yaml"), *CATALOGUE.glob("python_*.py")])


def expected_stderr(path: Path) -> str:
    error, hint = path.read_text().splitlines()[:2]
    assert error.startswith("# error: "), path.name
    assert hint.startswith("# hint: "), path.name
    text = "error: " + error.removeprefix("# error: ")
    if hint != "# hint: none":
        text += "\n  hint: " + hint.removeprefix("# hint: ")
    return text + "\n"


def test_catalogue_is_large_and_covers_both_front_ends():
    assert len(CASES) >= 30
    assert sum(p.suffix == ".py" for p in CASES) >= 10


@pytest.mark.parametrize("path", CASES, ids=[p.name for p in CASES])
def test_bad_spec_gives_its_pinned_message(path, tmp_path):
    output = tmp_path / "out"
    result = run_rfc("build", path.name, "-o", output, "--emit-ir", cwd=CATALOGUE)
    assert result.stderr == expected_stderr(path)
    assert result.returncode == 1
    assert result.stdout == ""
    assert "Traceback" not in result.stderr
    assert not output.exists()
    assert list(tmp_path.iterdir()) == []  # no staging folder left behind either


@pytest.mark.parametrize("path", CASES, ids=[p.name for p in CASES])
def test_check_rejects_it_as_build_does(path, monkeypatch, capsys):
    """`rfc check` (the real entry point, in process for speed) prints build's pinned message."""
    monkeypatch.chdir(CATALOGUE)
    monkeypatch.setattr(sys, "argv", ["rfc", "check", path.name])
    with pytest.raises(SystemExit) as exit_status:
        main()
    assert exit_status.value.code == 1
    captured = capsys.readouterr()
    assert captured.err == expected_stderr(path)
    assert captured.out == ""
