"""Start-up: `rfc --help` and `rfc check` import only what they use; the lazy commands are whole."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from rfc.cli import COMMANDS, load_command
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("cocotb", "myhdl", "numba", "matplotlib")

# Runs the command line in this process, then reports which heavy packages it imported.
PROBE = """
import atexit, json, sys
heavy = {heavy!r}
atexit.register(lambda: print(json.dumps(sorted(
    n for n in heavy if n in sys.modules)), file=sys.stderr))
sys.argv = ["rfc", *{args!r}]
from rfc.cli import main
main()
"""


def imported(*args: str) -> tuple[subprocess.CompletedProcess[str], list[str]]:
    code = PROBE.format(heavy=HEAVY, args=list(args))
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=False
    )
    return result, json.loads(result.stderr.strip().splitlines()[-1])


def test_help_imports_no_simulator_compiler_nor_plotting():
    result, heavy = imported("--help")
    assert result.returncode == 0
    assert "Commands" in result.stdout
    assert heavy == []


def test_check_of_an_hls_accelerator_system_imports_none_of_them():
    result, heavy = imported("check", "examples/sensor_hub/SensorHub.yaml")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("ok: ")
    assert heavy == []


def test_check_of_a_myhdl_accelerator_system_imports_only_myhdl():
    result, heavy = imported("check", "examples/quaternion_to_euler/project.yaml")
    assert result.returncode == 0, result.stderr
    assert heavy == ["myhdl"]  # the accelerator's own source imports it


@pytest.mark.parametrize("name", list(COMMANDS))
def test_the_help_summary_is_the_commands_own(name):
    command = load_command(name)
    assert command.name == name
    assert command.help.split("\n\n")[0].replace("\n", " ").strip() == COMMANDS[name].summary


def test_a_misspelt_command_is_suggested_its_near_misses():
    result = run_rfc("chek", "spec.yaml")
    assert result.returncode == 2
    assert "No such command 'chek'. Did you mean 'check', 'sched'?" in result.stderr
