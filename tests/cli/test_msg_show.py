"""`rfc msg show`: the command-line contract of docs/architecture.md."""

from __future__ import annotations

import json

from tests.support.cli import run_rfc
from tests.support.service_bag import SERVICE_TOPIC, bag_with_a_service_event


def show_json(*args):
    result = run_rfc("msg", "show", *args, "--json")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    return json.loads(result.stdout)


def test_quaternion_ros2_json():
    doc = show_json("geometry_msgs/Quaternion", "--middleware", "ros2")
    assert doc["type"] == "geometry_msgs/msg/Quaternion"
    assert doc["middleware"] == "ros2"
    assert doc["fixed_size"] == 36
    assert [
        (f["path"], f["type"], f["bits"], f["offset"], f["selected"]) for f in doc["fields"]
    ] == [
        ("x", "float64", 64, 4, True),
        ("y", "float64", 64, 12, True),
        ("z", "float64", 64, 20, True),
        ("w", "float64", 64, 28, True),
    ]


def test_quaternion_ros1_json():
    doc = show_json("geometry_msgs/Quaternion", "--middleware", "ros1")
    assert [f["offset"] for f in doc["fields"]] == [0, 8, 16, 24]
    assert doc["fixed_size"] == 32


def test_image_is_dynamic_after_frame_id():
    doc = show_json("sensor_msgs/Image")
    by_path = {f["path"]: f for f in doc["fields"]}
    assert by_path["header.frame_id"]["offset"] == 12
    assert by_path["header.frame_id"]["type"] == "string"
    assert all(
        by_path[p]["offset"] is None for p in ("height", "width", "encoding", "step", "data")
    )
    assert by_path["data"]["type"] == "uint8[]"
    assert doc["fixed_size"] is None


def test_selection_and_array_paths():
    doc = show_json(
        "geometry_msgs/PoseWithCovarianceStamped",
        "--include",
        "pose.covariance",
        "--exclude",
        "pose.covariance[0]",
    )
    selected = [f["path"] for f in doc["fields"] if f["selected"]]
    assert selected[0] == "pose.covariance[1]"
    assert selected[-1] == "pose.covariance[35]"
    assert len(selected) == 35


def test_element_fields_of_a_message_sequence():
    doc = show_json("tf2_msgs/TFMessage")
    (transforms,) = doc["fields"]
    assert transforms["type"] == "geometry_msgs/msg/TransformStamped[]"
    assert transforms["element"][3]["path"] == "child_frame_id"


def test_user_message_directory(examples_dir):
    doc = show_json(
        "franka_msgs/FrankaState", "-m", "ros1", "--msg-path", examples_dir / "franka" / "msg"
    )
    assert doc["type"] == "franka_msgs/FrankaState"
    assert any(f["path"] == "O_T_EE[15]" for f in doc["fields"])


def test_table_by_default():
    result = run_rfc("msg", "show", "geometry_msgs/Point")
    assert result.returncode == 0
    assert "geometry_msgs/msg/Point" in result.stdout
    assert "float64" in result.stdout
    assert "28" in result.stdout


def test_unknown_type_exits_1_with_suggestion_and_no_traceback():
    result = run_rfc("msg", "show", "geometry_msgs/Quaternoin", "--json")
    assert result.returncode == 1
    assert result.stdout == ""
    assert "unknown message type 'geometry_msgs/Quaternoin'" in result.stderr
    assert "did you mean 'geometry_msgs/Quaternion'" in result.stderr
    assert "Traceback" not in result.stderr


def test_missing_field_exits_1():
    result = run_rfc("msg", "show", "sensor_msgs/Image", "--include", "heigth")
    assert result.returncode == 1
    assert "has no field 'heigth'" in result.stderr
    assert "did you mean 'height'" in result.stderr


def test_bad_usage_exits_2():
    assert run_rfc("msg", "show").returncode == 2
    assert run_rfc("msg", "show", "std_msgs/String", "--middleware", "ros3").returncode == 2
    assert run_rfc("msg", "frobnicate").returncode == 2


def test_version_and_module_entry():
    result = run_rfc("--version")
    assert result.returncode == 0
    assert result.stdout.startswith("rfc ")


def test_a_bag_with_a_service_event_is_read_and_the_event_named(tmp_path):
    bag, _ = bag_with_a_service_event(tmp_path)
    result = run_rfc("msg", "show", "geometry_msgs/Point", "--bag", bag, "--json")
    assert result.returncode == 0, result.stderr
    assert [f["path"] for f in json.loads(result.stdout)["fields"]] == ["x", "y", "z"]
    assert f"{SERVICE_TOPIC} is a service or action, not a message; skipped" in result.stderr
