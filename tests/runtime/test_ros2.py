"""The generated node on a real ROS 2 graph: rclpy and Fast DDS, the logic simulated in GHDL.

A separate rclpy process publishes the inputs and receives the outputs; each answer is held to
the accelerators' Python references, one by one.
"""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types
from tests.runtime.ros2_graph import exchange
from tests.runtime.support import pose_messages, system_copy
from tests.support.cli import run_rfc

QUATERNION = "geometry_msgs/msg/Quaternion"
POINT = "geometry_msgs/msg/Point"
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"
ROOT = Path(__file__).resolve().parents[2]


def module_at(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(path.parent))
    try:
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(path.parent))
    return module


@pytest.fixture(scope="module")
def quaternion_build(tmp_path_factory):
    out = tmp_path_factory.mktemp("quaternion") / "build"
    spec = ROOT / "examples" / "quaternion_to_euler" / "project.yaml"
    result = run_rfc("build", spec, "-o", out)
    assert result.returncode == 0, result.stderr
    return out


def orientations(count: int) -> list[bytes]:
    """Random unit quaternions (a fixed seed), serialized by rosbags."""
    types = message_types("ros2")
    rng = np.random.default_rng(16)
    messages = []
    for q in rng.normal(size=(count, 4)):
        x, y, z, w = q / np.linalg.norm(q)
        message = types.build(QUATERNION, {"x": x, "y": y, "z": z, "w": w})
        messages.append(types.serialize(message, QUATERNION))
    return messages


def euler_references(inputs: list[bytes]) -> list[bytes]:
    """The accelerator's bit-accurate Python reference on each orientation."""
    accelerator = module_at(
        ROOT / "examples" / "quaternion_to_euler" / "accelerator.py", "_quaternion_reference"
    )
    types = message_types("ros2")
    return [
        types.serialize(
            accelerator.quaternion_to_euler_message(types.deserialize(data, QUATERNION)), POINT
        )
        for data in inputs
    ]


def quaternion_job(inputs: list[bytes]) -> dict:
    return {
        "input": "/imu/orientation",
        "input_type": QUATERNION,
        "output": "/imu/euler",
        "output_type": POINT,
        "messages": [data.hex() for data in inputs],
        "timeout": 120,
    }


def test_the_quaternion_node_answers_each_orientation_as_the_reference(quaternion_build, tmp_path):
    inputs = orientations(12)
    node = quaternion_build / "sw" / "quaternion_to_euler_node.py"
    answers = exchange(node, ["--device", "sim"], quaternion_job(inputs), tmp_path)
    expected = euler_references(inputs)
    for index, (answer, reference) in enumerate(zip(answers, expected, strict=True)):
        assert answer == reference, f"message {index}"


def test_the_node_runs_with_the_compiler_deleted(quaternion_build, tmp_path):
    """An installed copy holding rfc.runtime and the layers below it, no compiler module.

    sw/ and hw/ are moved too.
    """
    package = tmp_path / "site" / "rfc"
    shutil.copytree(ROOT / "runtime", package / "runtime")
    shutil.copytree(ROOT / "compiler" / "messages", package / "messages")
    for module in ("__init__.py", "errors.py", "user_code.py"):
        shutil.copy(ROOT / "compiler" / module, package / module)
    moved = tmp_path / "deployed"
    shutil.copytree(quaternion_build / "sw", moved / "sw")
    shutil.copytree(quaternion_build / "hw", moved / "hw")
    node = moved / "sw" / "quaternion_to_euler_node.py"
    site_packages = Path(np.__file__).parents[1]
    launcher = tmp_path / "launch.py"
    # Without site (-S) the editable install's finder is not loaded: only the copy is importable.
    launcher.write_text(
        "import importlib.util, runpy, sys\n"
        "import ros_wheels_bootstrapper  # what site would have run for the ROS wheels\n"
        "for name in ('rfc.driver', 'rfc.ir', 'rfc.spec', 'rfc.lower', 'rfc.toolchain'):\n"
        "    assert importlib.util.find_spec(name) is None, name\n"
        "sys.argv = sys.argv[1:]\n"
        "runpy.run_path(sys.argv[0], run_name='__main__')\n"
    )
    inputs = orientations(3)
    answers = exchange(
        launcher,
        [str(node), "--device", "sim"],
        quaternion_job(inputs),
        tmp_path,
        interpreter=(sys.executable, "-S"),
        env={"PYTHONPATH": f"{package.parent}:{site_packages}"},
    )
    assert answers == euler_references(inputs)
    assert "Traceback" not in (tmp_path / "node.log").read_text()


@pytest.mark.slow
def test_a_mixed_hardware_and_ros_sw_node_answers_as_its_references(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "build"
    result = run_rfc("build", spec, "-o", out)
    assert result.returncode == 0, result.stderr
    types = message_types("ros2")
    models = module_at(spec.parent / "passthrough.py", "_pose_mixed_models")
    inputs = [m.data for m in pose_messages(types, 6)]
    job = {
        "input": "/amcl_pose",
        "input_type": POSE,
        "output": "/pose_cleared",
        "output_type": POSE,
        "messages": [data.hex() for data in inputs],
        "timeout": 120,
    }
    answers = exchange(out / "sw" / "pose_mixed_node.py", ["--device", "sim"], job, tmp_path)
    for index, (answer, data) in enumerate(zip(answers, inputs, strict=True)):
        expected = types.serialize(models.clear_covariance(types.deserialize(data, POSE)), POSE)
        assert answer is not None, f"message {index} got no answer"
        # DDS may round a frame up to a multiple of 4 bytes
        assert answer[: len(expected)] == expected, index
        assert len(answer) - len(expected) < 4, index


DEAF_TOP = """\
library ieee;
use ieee.std_logic_1164.all;

-- The build's top level with a logic that never takes a PS-to-PL beat.
entity quaternion_to_euler_pl is
  port (
    aclk, aresetn : in std_logic;
    s_axis_mm2s_tdata : in std_logic_vector(63 downto 0);
    s_axis_mm2s_tkeep : in std_logic_vector(7 downto 0);
    s_axis_mm2s_tvalid, s_axis_mm2s_tlast : in std_logic;
    s_axis_mm2s_tready : out std_logic;
    m_axis_s2mm_tdata : out std_logic_vector(63 downto 0);
    m_axis_s2mm_tkeep : out std_logic_vector(7 downto 0);
    m_axis_s2mm_tvalid, m_axis_s2mm_tlast : out std_logic;
    m_axis_s2mm_tready : in std_logic
  );
end entity;

architecture deaf of quaternion_to_euler_pl is
begin
  s_axis_mm2s_tready <= '0';
  m_axis_s2mm_tdata <= (others => '0');
  m_axis_s2mm_tkeep <= (others => '0');
  m_axis_s2mm_tvalid <= '0';
  m_axis_s2mm_tlast <= '0';
end architecture;
"""


def test_a_logic_that_does_not_answer_ends_the_node_with_one_error(quaternion_build, tmp_path):
    deployed = tmp_path / "deployed"
    shutil.copytree(quaternion_build / "sw", deployed / "sw")
    (deployed / "hw").mkdir()
    (deployed / "hw" / "deaf.vhd").write_text(DEAF_TOP)
    (deployed / "hw" / "files.txt").write_text("deaf.vhd\n")
    job = {**quaternion_job(orientations(1)), "timeout": 30}
    node = deployed / "sw" / "quaternion_to_euler_node.py"
    answers = exchange(
        node, ["--device", "sim", "--answer-timeout", "2"], job, tmp_path, exits=True
    )
    assert answers == [None]
    assert (tmp_path / "node.status").read_text() == "1"
    log = (tmp_path / "node.log").read_text()
    assert "rfc node: the logic has not taken a PS→PL transfer in 2 s" in log
    assert "Traceback" not in log


def test_the_node_reads_what_the_logic_dropped_through_the_status_chunk(quaternion_build, tmp_path):
    """Damaged frames sent on to the logic (--send-malformed) come back as its drop counts.

    Fast DDS refuses to publish more bytes than a bounded type can hold, so no frame with
    trailing bytes reaches the node (tests/cli/test_sim_malformed.py sends those through a bag).
    """
    valid = orientations(6)
    damaged = {
        "truncated": [valid[0][:20], valid[1][:9]],
        "encoding": [b"\x00\x00" + valid[3][2:]] * 3,  # big-endian CDR: not what the logic reads
    }
    frames = [frame for kind in damaged.values() for frame in kind]
    job = {
        **quaternion_job([*frames, *valid]),
        "silent": list(range(len(frames))),
        "linger": 3,
    }
    node = quaternion_build / "sw" / "quaternion_to_euler_node.py"
    arguments = ["--device", "sim", "--send-malformed", "--status-period", "0.5"]
    answers = exchange(node, arguments, job, tmp_path)
    assert answers[len(frames) :] == euler_references(valid)
    log = (tmp_path / "node.log").read_text()
    counts = ", ".join(
        f"orientation_sub logic:{kind} {len(kind_frames)}" for kind, kind_frames in damaged.items()
    )
    assert f"rfc node: frames the logic dropped: {counts}" in log, log
