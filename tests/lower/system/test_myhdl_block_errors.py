"""A user's MyHDL block that fails to convert is one error naming it, not a traceback."""

from __future__ import annotations

from tests.runtime.support import system_copy
from tests.support.cli import run_rfc


def test_a_block_raising_while_converting_is_an_error_at_its_accelerator(tmp_path):
    # the pass-through pairs each output with an input; its input here lacks the orientation
    spec = system_copy(tmp_path, "pose_ros1.yaml", ("type: ROS-SW", "type: MyHDL"))
    out = tmp_path / "out"
    result = run_rfc("build", spec, "-o", out)
    assert result.returncode == 1
    assert result.stderr.startswith(
        f"error: {spec}:4:5: MyHDL accelerator 'PassStamped' (block 'pass_through' in "
        "passthrough.py) failed to convert: KeyError: "
    )
    assert "Traceback" not in result.stderr
    assert not out.exists()
