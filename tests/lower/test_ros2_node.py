"""The generated ROS 2 node: its files under sw/, its configuration, its lazy use of rclpy."""

from __future__ import annotations

import json
import subprocess
import sys

from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import message_types
from rfc.passes.frame_size import frame_bound
from tests.runtime.support import system_copy
from tests.support.cli import run_rfc


def test_build_writes_the_node_and_its_configuration(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    result = run_rfc("build", spec, "-o", out, "--no-hardware")
    assert result.returncode == 0, result.stderr
    config = json.loads((out / "sw" / "pose_mixed_node.json").read_text())
    assert config["spec"] == str(spec)
    assert config["node_name"] == "pose_mixed"
    assert config["devices"] == {"mm2s": "/dev/rfc_mm2s", "s2mm": "/dev/rfc_s2mm"}
    assert [(s["id"], s["block"], s["topic"]) for s in config["subscribers"]] == [
        (0, "Pose_sub", "/amcl_pose"),
        (1, "Pass2_in0_sub", ""),
    ]
    assert [(p["id"], p["block"]) for p in config["publishers"]] == [
        (0, "Pose_pub"),
        (1, "Pass_out0_pub"),
    ]
    # the largest PoseWithCovarianceStamped the logic accepts: frame_id at the default 4,096
    types = message_types("ros2")
    pose = flatten(types, "geometry_msgs/msg/PoseWithCovarianceStamped")
    assert config["max_transfer"] == 8 + frame_bound(pose, Limits())
    report = (out / "report.md").read_text()
    assert "| ROS 2 node | 1 |" in report
    node = out / "sw" / "pose_mixed_node.py"
    help_text = subprocess.run(
        [sys.executable, node, "--help"], capture_output=True, text=True, check=False
    )
    assert help_text.returncode == 0, help_text.stderr
    assert "--queue {per-subscriber,shared-fifo}" in help_text.stdout


def test_the_node_compiles_the_spec_then_needs_ros_2(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    assert run_rfc("build", spec, "-o", out, "--no-hardware").returncode == 0
    node = out / "sw" / "pose_mixed_node.py"
    result = subprocess.run(
        [sys.executable, node, "--mm2s", "/dev/null", "--s2mm", "/dev/null"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 1
    assert "cannot import ROS 2's Python client (rclpy); source a ROS 2" in result.stderr


def test_ros1_projects_get_no_node(tmp_path, examples_dir):
    out = tmp_path / "build"
    spec = examples_dir / "rotation_converter" / "RotationConverterNode.yaml"
    assert run_rfc("build", spec, "-o", out, "--no-hardware").returncode == 0
    assert not (out / "sw").exists()
