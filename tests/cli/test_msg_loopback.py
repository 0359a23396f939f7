"""`rfc msg loopback`: the command-line contract of docs/architecture.md, on the shared bags.

The suite samples each bag (the first messages of a type); `tools/bench_converters.py
--loopback` runs the whole bags at every width (figures in docs/converters.md).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Rosbag2Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from typer.testing import CliRunner

import rfc.cli.msg
from rfc.cli import app
from rfc.lib.converters.loopback_run import LoopbackReport, LoopbackResult
from rfc.messages.rosbags_adapter import (
    MessageTypes,
    Middleware,
    message_types,
    read_bag,
    write_bag,
)
from tests.conftest import shared_file
from tests.examples.multi_type.test_system import twist
from tests.support.cli import run_rfc

NAV2 = "bags/nav2_turtlebot.mcap"
CDR_TEST = "bags/cdr_test_0.mcap"
RESULT_KEYS = {"index", "equal", "subscriber_cycles", "publisher_cycles"}


def loopback_json(*args):
    result = run_rfc("msg", "loopback", *args, "--json")
    assert result.returncode == 0, result.stderr + result.stdout
    return json.loads(result.stdout)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("type_name", "bag", "topic", "width", "count"),
    [
        ("geometry_msgs/msg/PoseWithCovarianceStamped", NAV2, "/amcl_pose", 8, 4),
        ("nav_msgs/msg/Odometry", NAV2, "/odom", 32, 4),
        ("tf2_msgs/msg/TFMessage", NAV2, "/tf", 64, 40),
        ("test_msgs/msg/BasicTypes", CDR_TEST, None, 32, None),
        ("test_msgs/msg/Arrays", CDR_TEST, None, 8, None),
    ],
    ids=["amcl_pose-8", "odom-32", "tf-64", "BasicTypes-32", "Arrays-8"],
)
def test_recorded_messages_come_back_byte_exact(type_name, bag, topic, width, count):
    path = shared_file(bag)
    args = [type_name, "--bag", path, "--width", str(width)]
    args += ["--topic", topic] if topic else []
    args += ["--count", str(count)] if count else []
    doc = loopback_json(*args)
    assert set(doc) == {"type", "middleware", "width", "messages", "equal", "results"}
    assert (doc["type"], doc["middleware"], doc["width"]) == (type_name, "ros2", width)
    assert doc["equal"] is True
    frames = recorded_frames(path, type_name, topic, count)
    assert doc["messages"] == len(doc["results"]) == len(frames)
    assert [r["index"] for r in doc["results"]] == list(range(doc["messages"]))
    for result, frame in zip(doc["results"], frames, strict=True):
        assert set(result) == RESULT_KEYS
        assert result["equal"] is True
        # Neither side is faster than the bus: the fields are valid after the last beat came
        # in, the last beat goes out after all the frame's beats.
        beats = -(-len(frame) // (width // 8))
        assert result["subscriber_cycles"] >= beats - 1
        assert result["publisher_cycles"] >= beats


def recorded_frames(bag, type_name, topic, count):
    types = MessageTypes(Middleware.ROS2, bags=[bag])
    frames = [
        m.data
        for m in read_bag(bag, types, [topic] if topic else ())
        if types.resolve(m.type_name) == types.resolve(type_name)
    ]
    return frames[:count] if count else frames


def test_a_type_the_bag_lacks_is_one_error_naming_what_it_has():
    result = run_rfc("msg", "loopback", "sensor_msgs/msg/Imu", "--bag", shared_file(NAV2))
    assert result.returncode == 1
    assert result.stdout == ""
    assert "has no message of type sensor_msgs/msg/Imu" in result.stderr
    assert "nav_msgs/msg/Odometry" in result.stderr
    assert "Traceback" not in result.stderr


def test_a_misspelled_type_gets_a_suggestion():
    result = run_rfc("msg", "loopback", "nav_msgs/msg/Odometri", "--bag", shared_file(NAV2))
    assert result.returncode == 1
    assert "unknown message type 'nav_msgs/msg/Odometri'" in result.stderr
    assert "did you mean 'nav_msgs/msg/Odometry'" in result.stderr


def test_a_middleware_the_bag_was_not_recorded_with_is_refused():
    result = run_rfc(
        "msg", "loopback", "nav_msgs/msg/Odometry", "--bag", shared_file(NAV2), "-m", "ros1"
    )
    assert result.returncode == 1
    assert "was recorded with ROS 2, not ROS 1" in result.stderr


def test_a_missing_bag_is_refused(tmp_path):
    result = run_rfc("msg", "loopback", "nav_msgs/msg/Odometry", "--bag", tmp_path / "none.mcap")
    assert result.returncode == 1
    assert "does not exist" in result.stderr


def test_a_width_other_than_8_32_64_is_bad_usage():
    result = run_rfc(
        "msg", "loopback", "nav_msgs/msg/Odometry", "--bag", shared_file(NAV2), "--width", "16"
    )
    assert result.returncode == 2
    assert "16 is not a bus width" in result.stderr


@pytest.mark.parametrize("as_json", [True, False])
def test_a_mismatch_exits_1_after_printing_the_report(monkeypatch, tmp_path, as_json):
    report = LoopbackReport(
        "geometry_msgs/msg/Point",
        Middleware.ROS2,
        32,
        (LoopbackResult(0, True, 9, 10), LoopbackResult(1, False, 9, 10)),
    )
    monkeypatch.setattr(rfc.cli.msg, "loopback", lambda *args, **kwargs: report)
    bag = tmp_path / "points.mcap"
    bag.touch()
    args = ["msg", "loopback", "geometry_msgs/msg/Point", "--bag", str(bag)]
    result = CliRunner().invoke(app, [*args, "--json"] if as_json else args)
    assert result.exit_code == 1
    if as_json:
        doc = json.loads(result.stdout)
        assert doc["equal"] is False
        assert [r["equal"] for r in doc["results"]] == [True, False]
    else:
        assert "differ (indices)" in result.stdout


PAIR = "int32 a\nfloat64 b\nstring name\n"


def pair_bag(tmp_path, values):
    """A .db3 of my_msgs/msg/Pair recorded without definitions, and the folder defining it."""
    (tmp_path / "defs" / "my_msgs" / "msg").mkdir(parents=True)
    (tmp_path / "defs" / "my_msgs" / "msg" / "Pair.msg").write_text(PAIR)
    store = get_typestore(Stores.ROS2_HUMBLE)
    store.register(get_types_from_msg(PAIR, "my_msgs/msg/Pair"))
    pair = store.types["my_msgs/msg/Pair"]
    with Rosbag2Writer(tmp_path / "rec", version=9, storage_plugin=StoragePlugin.SQLITE3) as out:
        connection = out.add_connection(
            "/pair", "my_msgs/msg/Pair", msgdef="", rihs01="RIHS01_" + "0" * 64
        )
        for stamp, (a, b, name) in enumerate(values, 1):
            out.write(connection, stamp, store.serialize_cdr(pair(a, b, name), "my_msgs/msg/Pair"))
    (bag,) = (tmp_path / "rec").glob("*.db3")
    return bag, tmp_path / "defs"


def test_a_bag_without_definitions_loops_back_with_msg_path_exclude_and_a_relative_keep(tmp_path):
    bag, defs = pair_bag(tmp_path, [(1, 2.5, "abc"), (-7, 0.125, "")])
    missing = run_rfc("msg", "loopback", "my_msgs/msg/Pair", "--bag", bag)
    assert missing.returncode == 1
    assert "--msg-path" in missing.stderr
    result = run_rfc(
        "msg", "loopback", "my_msgs/msg/Pair", "--bag", bag, "--msg-path", defs,
        "--exclude", "b", "--keep", "kept", "--json", cwd=tmp_path,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert (doc["messages"], doc["equal"]) == (2, True)
    assert (tmp_path / "kept" / "frames.txt").is_file()


def test_a_bag_without_messages_says_so(tmp_path):
    bag, defs = pair_bag(tmp_path, [])
    result = run_rfc("msg", "loopback", "my_msgs/msg/Pair", "--bag", bag, "--msg-path", defs)
    assert result.returncode == 1
    assert "holds no messages at all" in result.stderr


def test_verilator_gives_ghdls_bytes_and_cycles(tmp_path):
    rng = np.random.default_rng(11)
    types = message_types("ros2")
    kind = "geometry_msgs/msg/TwistStamped"
    messages = []
    for index in range(9):  # frame ids of 0 … 8 bytes: every length modulo the 32-bit bus
        values = twist(rng)
        values["header"]["frame_id"] = "f" * index
        messages.append(
            ("/cmd_vel", 1000 * (index + 1), types.serialize(types.build(kind, values), kind))
        )
    bag = tmp_path / "twists.mcap"
    write_bag(bag, types, {"/cmd_vel": kind}, messages)
    reports = {
        simulator: loopback_json(kind, "--bag", bag, "--width", "32", "--simulator", simulator)
        for simulator in ("ghdl", "verilator")
    }
    assert reports["ghdl"]["equal"] is True
    assert reports["verilator"] == reports["ghdl"]
