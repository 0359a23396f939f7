"""`rfc sim`: a bag through the whole system, out to a bag, with a complete account."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.conftest import shared_file
from tests.runtime.support import pose_messages, system_copy
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
ECHO = ("--top-provider", "tests.runtime.echo_top:simulation_top")
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"
TO_SOFTWARE = ("type: MyHDL", "type: ROS-SW")


def sim(spec, bag, out, *extra):
    result = run_rfc("sim", spec, "--bag", bag, "--out", out, *extra, "--json", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def messages_of(path, middleware="ros2"):
    return [(m.topic, m.timestamp_ns, m.data) for m in read_bag(path, message_types(middleware))]


def test_mixed_system_replays_a_real_bag_through_ghdl_as_in_software(tmp_path):
    bag = shared_file("bags/nav2_turtlebot.mcap")
    (tmp_path / "hw").mkdir()
    (tmp_path / "sw").mkdir()
    hardware = system_copy(tmp_path / "hw", "pose_mixed.yaml")
    software = system_copy(tmp_path / "sw", "pose_mixed.yaml", TO_SOFTWARE)
    account = sim(hardware, bag, tmp_path / "hw.mcap")
    assert account["received"] == {"/amcl_pose": 135}
    assert account["to_logic"] == {"Pose_sub": 135, "Pass2_in0_sub": 135}
    assert account["from_logic"] == {"Pass_out0_pub": 135, "Pose_pub": 135}
    assert account["software_calls"] == {"Clear": 135}
    assert account["published"] == {"/pose_cleared": 135}
    assert account["dropped"] == []
    in_software = sim(software, bag, tmp_path / "sw.mcap")
    assert in_software["software_calls"] == {"Pass": 135, "Clear": 135, "Pass2": 135}
    assert in_software["to_logic"] == {}
    outputs = messages_of(tmp_path / "hw.mcap")
    assert outputs == messages_of(tmp_path / "sw.mcap")
    # the oracle: rosbags' reading of the input, changed as the software accelerator says
    types = message_types("ros2")
    inputs = list(read_bag(bag, types, ["/amcl_pose"]))
    for source, (topic, stamp, data) in zip(inputs, outputs, strict=True):
        before, after = types.deserialize(source.data, POSE), types.deserialize(data, POSE)
        assert (topic, stamp) == ("/pose_cleared", source.timestamp_ns)
        assert after.pose.pose.position.x == 2 * before.pose.pose.position.x
        assert after.pose.pose.orientation == before.pose.pose.orientation
        assert after.header == before.header
        assert not np.any(after.pose.covariance)


def test_ros1_bag_replays_in_software_with_the_selection_applied(tmp_path):
    bag = shared_file("bags/ROS_example.bag")
    spec = system_copy(tmp_path, "pose_ros1.yaml")
    out = tmp_path / "out.bag"
    result = run_rfc("sim", spec, "--bag", bag, "--out", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert "/groundtruth_position" in result.stdout
    assert "wrote 12765 messages" in result.stderr
    types = message_types("ros1")
    inputs = list(read_bag(bag, types, ["groundtruth"]))
    outputs = list(read_bag(out, types))
    assert len(outputs) == len(inputs) == 12765
    name = "geometry_msgs/msg/PoseStamped"
    for source, output in zip(inputs[::500], outputs[::500], strict=True):
        before, after = types.deserialize(source.data, name), types.deserialize(output.data, name)
        assert output.timestamp_ns == source.timestamp_ns
        assert (after.header, after.pose.position) == (before.header, before.pose.position)
        assert (after.pose.orientation.x, after.pose.orientation.w) == (0.0, 0.0)


@pytest.fixture
def small_bag(tmp_path):
    types = message_types("ros2")
    messages = pose_messages(types, 4)
    path = tmp_path / "in.mcap"
    write_bag(
        path, types, {"/amcl_pose": POSE}, [(m.topic, m.timestamp_ns, m.data) for m in messages]
    )
    return path


def test_db3_output_and_the_shared_fifo_policy(tmp_path, small_bag):
    spec = system_copy(tmp_path, "pose_mixed.yaml", TO_SOFTWARE)
    account = sim(spec, small_bag, tmp_path / "out.db3", "--queue", "shared-fifo")
    assert account["published"] == {"/pose_cleared": 4}
    assert [t for t, _, _ in messages_of(tmp_path / "out.db3")] == ["/pose_cleared"] * 4


@pytest.mark.parametrize(
    ("edit", "out_name", "message"),
    [
        (("topic: /amcl_pose", "topic: /amcl_psoe"), "out.mcap", "has no topic '/amcl_psoe'"),
        (None, "out.txt", "cannot tell the bag format of"),
        (None, "out.bag", "would be a ROS 1 bag, but the messages are ROS 2"),
        (("top: clear_covariance", "top: clear"), "out.mcap", "defines no function 'clear'"),
    ],
)
def test_bad_input_is_one_clear_error_and_nothing_is_written(
    tmp_path, small_bag, edit, out_name, message
):
    spec = system_copy(tmp_path, "pose_mixed.yaml", TO_SOFTWARE, *([edit] if edit else []))
    out = tmp_path / out_name
    result = run_rfc("sim", spec, "--bag", small_bag, "--out", out, cwd=ROOT)
    assert result.returncode == 1
    assert message in result.stderr
    assert "Traceback" not in result.stderr
    assert not out.exists()


def test_a_missing_topic_suggests_the_closest(tmp_path, small_bag):
    spec = system_copy(
        tmp_path, "pose_mixed.yaml", TO_SOFTWARE, ("topic: /amcl_pose", "topic: /amcl_psoe")
    )
    result = run_rfc("sim", spec, "--bag", small_bag, "--out", tmp_path / "o.mcap", cwd=ROOT)
    assert "pose_mixed.yaml:" in result.stderr
    assert "did you mean '/amcl_pose'?" in result.stderr


def test_a_bag_type_other_than_the_subscribers_is_refused(tmp_path):
    types = message_types("ros2")
    point = "geometry_msgs/msg/Point"
    data = types.serialize(types.build(point, {"x": 1.0, "y": 2.0, "z": 3.0}), point)
    bag = tmp_path / "points.mcap"
    write_bag(bag, types, {"/amcl_pose": point}, [("/amcl_pose", 1, data)])
    spec = system_copy(tmp_path, "pose_mixed.yaml", TO_SOFTWARE)
    result = run_rfc("sim", spec, "--bag", bag, "--out", tmp_path / "o.mcap", cwd=ROOT)
    assert result.returncode == 1
    assert "topic '/amcl_pose' of bag '" in result.stderr
    assert (
        "' carries geometry_msgs/msg/Point, but subscriber 'Pose_sub' takes "
        "geometry_msgs/msg/PoseWithCovarianceStamped" in result.stderr
    )
    assert not (tmp_path / "o.mcap").exists()


def test_myhdl_and_ghdl_backends_give_the_same_bag(tmp_path):
    types = message_types("ros2")
    messages = pose_messages(types, 8)
    bag = tmp_path / "pairs.mcap"
    # pairs 100 ns apart: the second of each waits in its queue while the first is in the logic
    stamps = [
        m.timestamp_ns if i % 2 == 0 else messages[i - 1].timestamp_ns + 100
        for i, m in enumerate(messages)
    ]
    write_bag(
        bag,
        types,
        {"/amcl_pose": POSE},
        [(m.topic, s, m.data) for m, s in zip(messages, stamps, strict=True)],
    )
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    accounts = {
        backend: sim(
            spec,
            bag,
            tmp_path / f"{backend}.mcap",
            *ECHO,
            "--backend",
            backend,
            "--drain-cycles",
            "300",
        )
        for backend in ("ghdl", "myhdl")
    }
    assert accounts["ghdl"] | {"out": ""} == accounts["myhdl"] | {"out": ""}
    assert accounts["ghdl"]["published"] == {"/pose_cleared": 8}
    assert messages_of(tmp_path / "ghdl.mcap") == messages_of(tmp_path / "myhdl.mcap")


def test_myhdl_backend_needs_a_myhdl_design(tmp_path, small_bag):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    result = run_rfc(
        "sim",
        spec,
        "--bag",
        small_bag,
        "--out",
        tmp_path / "o.mcap",
        "--backend",
        "myhdl",
        "--top-provider",
        "tests.runtime.support:vhdl_only_top",
        cwd=ROOT,
    )
    assert result.returncode == 1
    assert "is not a MyHDL design, so it cannot run in MyHDL" in result.stderr
    assert not (tmp_path / "o.mcap").exists()


def test_listing_1s_hls_accelerator_is_c_simulated_with_its_scalar_arguments(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    bag = tmp_path / "q.bag"
    types = message_types("ros1")
    rng = np.random.default_rng(2)
    quaternions = rng.normal(size=(6, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    name = "geometry_msgs/msg/Quaternion"
    data = [types.serialize(types.build(name, dict(zip("xyzw", map(float, q), strict=True))), name)
            for q in quaternions]  # fmt: skip
    write_bag(bag, types, {"/Quaternion_sub": name},
              [("/Quaternion_sub", i + 1, d) for i, d in enumerate(data)])  # fmt: skip
    spec = ROOT / "examples/rotation_converter/RotationConverterNode.yaml"  # Listing 1: HLS
    account = sim(spec, bag, tmp_path / "o.bag")
    assert account["software_calls"] == {"QuatToEuler_acc": len(quaternions)}
    points = [types.deserialize(m.data, m.type_name) for m in read_bag(tmp_path / "o.bag", types)]
    for (x, y, z, w), point in zip(quaternions, points, strict=True):
        roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1, 1))
        yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        assert np.allclose([point.x, point.y, point.z], [roll, pitch, yaw], rtol=0, atol=1e-12)


def test_a_software_function_failing_in_the_simulator_is_one_error(tmp_path, small_bag):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    with (tmp_path / "passthrough.py").open("a") as models:
        models.write("\n\ndef clear_covariance(message):\n    raise ValueError('boom')\n")
    out = tmp_path / "o.mcap"
    result = run_rfc(
        "sim", spec, "--bag", small_bag, "--out", out, "--backend", "myhdl", *ECHO, cwd=ROOT
    )
    assert result.returncode == 1
    assert "ROS-SW accelerator 'Clear' raised ValueError: boom (call 1)" in result.stderr
    assert "Traceback" not in result.stderr
    assert not out.exists()


TWO_TOPICS = """
project: {name: TwoTopics, scheduler: LRU}
accelerators:
  - name: Pass
    type: ROS-SW
    sources: ./identity.py
    reference: ./identity.py:identity
    interface: {input: [{message: geometry_msgs/Point}], output: [{message: geometry_msgs/Point}]}
blocks:
  - {name: a_sub, type: ROS>accelerator, message: geometry_msgs/Point, topic: /a,
     outgoing: [{name: a_acc}]}
  - {name: b_sub, type: ROS>accelerator, message: geometry_msgs/Point, topic: /b,
     outgoing: [{name: b_acc}]}
  - {name: a_acc, type: Pass, outgoing: [{name: a_pub}]}
  - {name: b_acc, type: Pass, outgoing: [{name: b_pub}]}
  - {name: a_pub, type: accelerator>ROS, message: geometry_msgs/Point, topic: /a_out}
  - {name: b_pub, type: accelerator>ROS, message: geometry_msgs/Point, topic: /b_out}
"""


def two_topic_system(tmp_path):
    (tmp_path / "identity.py").write_text("def identity(message):\n    return message\n")
    (tmp_path / "two.yaml").write_text(TWO_TOPICS)
    types = message_types("ros2")
    point = "geometry_msgs/msg/Point"
    inputs = [
        (topic, 1000 * i, types.serialize(types.build(point, {"x": i, "y": 0, "z": 0}), point))
        for i in range(1, 9)
        for topic in ("/a", "/b")
    ]
    write_bag(tmp_path / "in.mcap", types, {"/a": point, "/b": point}, inputs)
    return tmp_path / "two.yaml", inputs


def test_limit_and_topics_replay_only_the_first_messages_of_the_topics_named(tmp_path):
    spec, inputs = two_topic_system(tmp_path)
    account = sim(
        spec, tmp_path / "in.mcap", tmp_path / "out.mcap", "--topics", "/b", "--limit", "3"
    )
    assert account["received"] == {"/b": 3}
    assert account["published"] == {"/b_out": 3}
    expected = [("/b_out", stamp, data) for topic, stamp, data in inputs if topic == "/b"][:3]
    assert messages_of(tmp_path / "out.mcap") == expected


def test_topics_must_be_subscribed(tmp_path):
    spec, _ = two_topic_system(tmp_path)
    result = run_rfc(
        "sim", spec, "--bag", tmp_path / "in.mcap", "--out", tmp_path / "o.mcap", "--topics", "/c"
    )
    assert result.returncode == 1
    assert "--topics names '/c', which no subscriber of the spec takes" in result.stderr
    assert not (tmp_path / "o.mcap").exists()
