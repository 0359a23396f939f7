"""The generated node: its files under sw/, its runtime plan, its lazy use of rclpy and rospy."""

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


def test_build_writes_the_node_its_plan_and_the_software_modules(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    result = run_rfc("build", spec, "-o", out, "--no-hardware")
    assert result.returncode == 0, result.stderr
    text = (out / "sw" / "pose_mixed_plan.json").read_text()
    assert str(tmp_path) not in text  # nothing of the build machine
    config = json.loads(text)
    assert config["node_name"] == "pose_mixed"
    assert config["software"][0]["module"] == "passthrough.py"
    copied = (out / "sw" / "passthrough.py").read_text()
    assert copied == (spec.parent / "passthrough.py").read_text()
    assert "geometry_msgs/msg/PoseWithCovarianceStamped" in config["messages"]
    assert config["devices"] == {"mm2s": "/dev/rfc_mm2s", "s2mm": "/dev/rfc_s2mm"}
    assert [(s["id"], s["block"]) for s in config["subscribers"]] == [
        (0, "Pose_sub"),
        (1, "Pass2_in0_sub"),
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
    assert "--device {dma,pynq,sim}" in help_text.stdout


def test_ros1_projects_get_a_rospy_node_with_md5_sums(tmp_path, examples_dir):
    out = tmp_path / "build"
    spec = examples_dir / "rotation_converter" / "RotationConverterNode.yaml"
    assert run_rfc("build", spec, "-o", out, "--no-hardware").returncode == 0
    plan = json.loads((out / "sw" / "rotation_converter_node_plan.json").read_text())
    assert plan["middleware"] == "ros1"
    quaternion = plan["messages"]["geometry_msgs/msg/Quaternion"]
    assert quaternion["md5"] == "a779879fadf0160734f906b8c19c7004"  # ROS 1's own sum
    result = subprocess.run(
        [sys.executable, out / "sw" / "rotation_converter_node_node.py"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 1
    assert "cannot import ROS 1's Python client (rospy)" in result.stderr
    assert "Traceback" not in result.stderr


def test_a_missing_dma_device_is_one_error_naming_it(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    assert run_rfc("build", spec, "-o", out, "--no-hardware").returncode == 0
    missing = tmp_path / "rfc_mm2s"
    result = subprocess.run(
        [sys.executable, out / "sw" / "pose_mixed_node.py", "--mm2s", missing],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 1
    assert f"the DMA device {missing} does not exist" in result.stderr
    assert "Traceback" not in result.stderr
