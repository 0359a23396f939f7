"""Binary or foreign files given as specs, sources or bags: one plain message, exit 1."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.conftest import shared_file
from tests.runtime.support import system_copy
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
LISTING_1 = ROOT / "examples" / "rotation_converter"
BINARY = bytes(range(256)) * 8  # NUL bytes and bytes that are not UTF-8


def _refused(result, message):
    assert result.returncode == 1
    assert message in result.stderr
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize("name", ["spec.yaml", "spec.py"])
@pytest.mark.parametrize("command", ["check", "build"])
def test_a_binary_spec_is_not_a_spec(tmp_path, name, command):
    (tmp_path / name).write_bytes(BINARY)
    result = run_rfc(command, name, cwd=tmp_path)
    _refused(result, f"error: '{name}' is not a spec: it is binary, not YAML or Python text")
    assert not (tmp_path / "build").exists()


def test_latin1_text_is_not_a_spec_and_names_the_byte(tmp_path):
    (tmp_path / "spec.yaml").write_bytes("project:\n  name: Caf\xe9\n".encode("latin-1"))
    _refused(run_rfc("check", "spec.yaml", cwd=tmp_path), "(byte 20 is not UTF-8)")


def test_a_binary_source_is_not_a_source(tmp_path):
    for path in LISTING_1.iterdir():
        shutil.copy(path, tmp_path / path.name)
    (tmp_path / "QuaternionToEulerConverter.cpp").write_bytes(BINARY)
    result = run_rfc("build", "RotationConverterNode.yaml", "-o", "out", cwd=tmp_path)
    _refused(
        result,
        "RotationConverterNode.yaml:8:14: 'QuaternionToEulerConverter.cpp' is not a source: "
        "it is binary, not HLS text",
    )


def test_random_bytes_are_not_a_bag(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml", ("type: MyHDL", "type: ROS-SW"))
    (tmp_path / "in.mcap").write_bytes(BINARY)
    result = run_rfc("sim", spec, "--bag", tmp_path / "in.mcap", "--out", tmp_path / "o.mcap")
    _refused(result, f"'{tmp_path / 'in.mcap'}' is not a bag")
    assert not (tmp_path / "o.mcap").exists()


def test_a_ros1_bag_given_to_a_ros2_project_says_so(tmp_path):
    bag = shared_file("bags/ROS_example.bag")
    spec = system_copy(tmp_path, "pose_mixed.yaml", ("type: MyHDL", "type: ROS-SW"))
    result = run_rfc("sim", spec, "--bag", bag, "--out", tmp_path / "o.mcap")
    _refused(result, f"'{bag}' is a ROS 1 bag, with ROS 1 messages, but the project is ROS 2")
