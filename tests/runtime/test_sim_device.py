"""The ``sim`` transport's errors: what a user can get wrong is one message, exit status 1."""

from __future__ import annotations

import subprocess
import sys

from tests.runtime.support import system_copy
from tests.support.cli import run_rfc


def test_sim_on_a_build_without_logic_says_how_to_get_it(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    assert run_rfc("build", spec, "-o", out, "--no-hardware").returncode == 0
    result = subprocess.run(
        [sys.executable, out / "sw" / "pose_mixed_node.py", "--device", "sim"],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert result.returncode == 1
    assert "this build holds no logic to simulate (it was built with --no-hardware)" in (
        result.stderr
    )
    assert "Traceback" not in result.stderr


def test_sim_without_the_logic_beside_sw_names_the_missing_file_list(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    assert run_rfc("build", spec, "-o", out).returncode == 0
    (out / "hw" / "files.txt").unlink()
    result = subprocess.run(
        [sys.executable, out / "sw" / "pose_mixed_node.py", "--device", "sim"],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert result.returncode == 1
    assert f"the logic's file list {out / 'hw' / 'files.txt'} is missing" in result.stderr
    assert "Traceback" not in result.stderr
