"""`rfc sim --out`: an existing file that is not a bag is never replaced without --force."""

from __future__ import annotations

from pathlib import Path

import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.runtime.support import pose_messages, system_copy
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"
TO_SOFTWARE = ("type: MyHDL", "type: ROS-SW")


@pytest.fixture
def software_system(tmp_path):
    types = message_types("ros2")
    bag = tmp_path / "in.mcap"
    rows = [(m.topic, m.timestamp_ns, m.data) for m in pose_messages(types, 3)]
    write_bag(bag, types, {"/amcl_pose": POSE}, rows)
    return system_copy(tmp_path, "pose_mixed.yaml", TO_SOFTWARE), bag


def _sim(spec, bag, out, *extra):
    return run_rfc("sim", spec, "--bag", bag, "--out", out, *extra, cwd=ROOT)


def test_an_existing_file_that_is_not_a_bag_is_refused(tmp_path, software_system):
    out = tmp_path / "thesis.mcap"
    out.write_text("not a bag, and precious\n")
    result = _sim(*software_system, out)
    assert result.returncode == 1
    assert f"--out '{out}' exists and is not a bag; refusing to replace it" in result.stderr
    assert "pass --force" in result.stderr
    assert "Traceback" not in result.stderr
    assert out.read_text() == "not a bag, and precious\n"


def test_force_replaces_it_and_an_earlier_output_bag_is_replaced_without(tmp_path, software_system):
    out = tmp_path / "out.mcap"
    out.write_text("not a bag\n")
    assert _sim(*software_system, out, "--force").returncode == 0
    assert len(list(read_bag(out, message_types("ros2")))) == 3
    result = _sim(*software_system, out)  # now a bag: a previous output, replaced as before
    assert result.returncode == 0, result.stderr
    assert len(list(read_bag(out, message_types("ros2")))) == 3
