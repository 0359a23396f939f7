"""Message definitions from the stores, user directories and bags."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import (
    MessageTypes,
    Middleware,
    bag_topics,
    canonical_name,
    message_types,
    read_bag,
    skipped_topics,
    write_bag,
)
from tests.conftest import shared_file
from tests.support.service_bag import SERVICE_TOPIC, bag_with_a_service_event


def test_canonical_names():
    assert canonical_name("geometry_msgs/Quaternion") == "geometry_msgs/msg/Quaternion"
    assert canonical_name("geometry_msgs/msg/Quaternion") == "geometry_msgs/msg/Quaternion"
    assert canonical_name("/std_msgs/Header") == "std_msgs/msg/Header"


@pytest.mark.parametrize("distro", ["foxy", "humble", "iron", "jazzy"])
def test_ros2_distros_are_selectable(distro):
    types = MessageTypes(Middleware.ROS2, distro)
    assert types.resolve("sensor_msgs/Image") == "sensor_msgs/msg/Image"


def test_unknown_distro_is_an_error_with_a_suggestion():
    with pytest.raises(RfcError, match=r"(?s)unknown ROS 2 distro 'humbel'.*did you mean 'humble'"):
        MessageTypes(Middleware.ROS2, "humbel")
    with pytest.raises(RfcError, match="unknown ROS 1 distro 'humble'"):
        MessageTypes(Middleware.ROS1, "humble")


def test_msg_path_must_exist(tmp_path):
    with pytest.raises(RfcError, match="does not exist"):
        MessageTypes(msg_paths=[tmp_path / "nope"])
    with pytest.raises(RfcError, match=r"holds no \.msg or \.idl files"):
        MessageTypes(msg_paths=[tmp_path])


def test_msg_path_with_a_broken_definition(tmp_path):
    pkg = tmp_path / "my_msgs" / "msg"
    pkg.mkdir(parents=True)
    (pkg / "Broken.msg").write_text("float64[ x\n")
    with pytest.raises(RfcError, match=r"Broken\.msg: not a valid message definition"):
        MessageTypes(msg_paths=[tmp_path])


def test_a_missing_dependency_blocks_only_the_types_that_use_it(tmp_path):
    pkg = tmp_path / "my_msgs" / "msg"
    pkg.mkdir(parents=True)
    (pkg / "Uses.msg").write_text("other_msgs/Missing thing\n")
    (pkg / "Wraps.msg").write_text("my_msgs/Uses inner\n")
    (pkg / "Fine.msg").write_text("int32 a\n")
    types = MessageTypes(msg_paths=[tmp_path])
    assert [f.path for f in flatten(types, "my_msgs/Fine").fields] == ["a"]
    with pytest.raises(RfcError) as excinfo:
        types.resolve("my_msgs/Uses")
    assert "my_msgs/msg/Uses field 'thing' has type 'other_msgs/msg/Missing'" in str(excinfo.value)
    assert "--msg-path" in str(excinfo.value)
    with pytest.raises(RfcError, match="uses my_msgs/msg/Uses, which is unresolved"):
        types.resolve("my_msgs/Wraps")


def test_msg_path_order_does_not_matter(tmp_path):
    (tmp_path / "a" / "top_msgs" / "msg").mkdir(parents=True)
    (tmp_path / "b" / "base_msgs" / "msg").mkdir(parents=True)
    (tmp_path / "a" / "top_msgs" / "msg" / "Top.msg").write_text("base_msgs/Base base\n")
    (tmp_path / "b" / "base_msgs" / "msg" / "Base.msg").write_text("float32 value\n")
    for order in ([tmp_path / "a", tmp_path / "b"], [tmp_path / "b", tmp_path / "a"]):
        layout = flatten(MessageTypes(msg_paths=order), "top_msgs/Top")
        assert [f.path for f in layout.fields] == ["base.value"]


def test_idl_definitions_are_read(tmp_path):
    (tmp_path / "idl_msgs" / "msg").mkdir(parents=True)
    (tmp_path / "idl_msgs" / "msg" / "Reading.idl").write_text(
        "module idl_msgs { module msg { struct Reading { double value; string label; }; }; };\n"
    )
    layout = flatten(MessageTypes(msg_paths=[tmp_path]), "idl_msgs/msg/Reading")
    assert [(f.path, f.ros_type) for f in layout.fields] == [
        ("value", "float64"),
        ("label", "string"),
    ]


def test_a_bag_with_a_service_schema_keeps_its_messages(tmp_path):
    bag, frame = bag_with_a_service_event(tmp_path)
    types = MessageTypes(Middleware.ROS2, bags=[bag])
    assert [(m.topic, m.data) for m in read_bag(bag, types)] == [("/p", frame)]
    assert skipped_topics(bag) == (SERVICE_TOPIC,)


def test_package_folder_without_msg_subfolder(tmp_path):
    (tmp_path / "flat_msgs").mkdir()
    (tmp_path / "flat_msgs" / "Pair.msg").write_text("int32 a\nstring b\n")
    types = MessageTypes(Middleware.ROS2, msg_paths=[tmp_path / "flat_msgs"])
    assert [f.path for f in flatten(types, "flat_msgs/Pair").fields] == ["a", "b"]


def test_definitions_embedded_in_a_bag():
    bag = shared_file("bags/cdr_test_0.mcap")
    types = MessageTypes(Middleware.ROS2, bags=[bag])
    arrays = flatten(types, "test_msgs/msg/Arrays")
    assert arrays.field("basic_types_values[2].uint64_value").ros_type == "uint64"
    assert arrays.field("string_values[0]").ros_type == "string"


def test_missing_bag_is_an_error(tmp_path):
    with pytest.raises(RfcError, match="does not exist"):
        MessageTypes(Middleware.ROS2, bags=[tmp_path / "missing.mcap"])


@pytest.mark.parametrize(
    ("middleware", "suffix"), [("ros2", ".mcap"), ("ros2", ".db3"), ("ros1", ".bag")]
)
def test_written_bags_read_back_with_every_topic(tmp_path, middleware, suffix):
    types = message_types(middleware)
    point = "geometry_msgs/msg/Point"
    data = types.serialize(types.build(point, {"x": 1.0, "y": -2.0, "z": 0.5}), point)
    path = tmp_path / f"out{suffix}"
    write_bag(path, types, {"/p": point, "/silent": point}, [("/p", 5, data), ("/p", 9, data)])
    assert bag_topics(path, types) == {"/p": point, "/silent": point}
    assert bag_topics(path, types, counts=True) == {"/p": 2, "/silent": 0}
    assert [(m.topic, m.timestamp_ns, m.data) for m in read_bag(path, types)] == [
        ("/p", 5, data),
        ("/p", 9, data),
    ]
    assert sorted(p.name for p in tmp_path.iterdir()) == [path.name]


def test_a_failed_bag_write_leaves_nothing(tmp_path):
    types = message_types("ros2")
    path = tmp_path / "out.mcap"
    with pytest.raises(KeyError):
        write_bag(path, types, {}, [("/unknown", 1, b"")])
    assert list(tmp_path.iterdir()) == []
