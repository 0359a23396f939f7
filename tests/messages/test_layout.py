"""Flattened layouts: paths, widths, offsets, alignment (docs/architecture.md, Message layouts)."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError
from rfc.messages.layout import FieldKind, flatten
from rfc.messages.rosbags_adapter import MessageTypes, Middleware, message_types


def offsets(layout):
    return {field.path: field.offset for field in layout.fields}


@pytest.mark.parametrize(
    ("middleware", "expected", "size"),
    [(Middleware.ROS2, [4, 12, 20, 28], 36), (Middleware.ROS1, [0, 8, 16, 24], 32)],
)
def test_quaternion_offsets(middleware, expected, size):
    layout = flatten(message_types(middleware), "geometry_msgs/Quaternion")
    assert [(f.path, f.ros_type, f.bits) for f in layout.fields] == [
        (axis, "float64", 64) for axis in "xyzw"
    ]
    assert [f.offset for f in layout.fields] == expected
    assert layout.fixed_size == size


def test_short_and_full_names_are_the_same_type():
    types = message_types(Middleware.ROS2)
    assert flatten(types, "geometry_msgs/Quaternion") is flatten(
        types, "geometry_msgs/msg/Quaternion"
    )


def test_image_fields_after_frame_id_are_dynamic():
    layout = flatten(message_types(Middleware.ROS2), "sensor_msgs/Image")
    assert offsets(layout) == {
        "header.stamp.sec": 4,
        "header.stamp.nanosec": 8,
        "header.frame_id": 12,
        "height": None,
        "width": None,
        "encoding": None,
        "is_bigendian": None,
        "step": None,
        "data": None,
    }
    assert layout.fixed_size is None
    data = layout.field("data")
    assert (data.ros_type, data.kind, data.bits, data.align) == (
        "uint8[]",
        FieldKind.SEQUENCE,
        8,
        4,
    )


def test_cdr_pads_a_float64_to_eight_bytes_of_payload():
    layout = flatten(message_types(Middleware.ROS2), "nav_msgs/MapMetaData")
    assert offsets(layout) == {
        "map_load_time.sec": 4,
        "map_load_time.nanosec": 8,
        "resolution": 12,
        "width": 16,
        "height": 20,
        # payload position 20 is padded to 24: frame offset 28, not 24.
        "origin.position.x": 28,
        "origin.position.y": 36,
        "origin.position.z": 44,
        "origin.orientation.x": 52,
        "origin.orientation.y": 60,
        "origin.orientation.z": 68,
        "origin.orientation.w": 76,
    }
    assert layout.fixed_size == 84
    ros1 = flatten(message_types(Middleware.ROS1), "nav_msgs/MapMetaData")
    assert ros1.field("origin.position.x").offset == 20
    assert ros1.fixed_size == 76


def test_a_trailing_bool_is_not_padded():
    roi = flatten(message_types(Middleware.ROS2), "sensor_msgs/RegionOfInterest")
    assert offsets(roi) == {
        "x_offset": 4,
        "y_offset": 8,
        "height": 12,
        "width": 16,
        "do_rectify": 20,
    }
    assert roi.fixed_size == 21


def test_fixed_arrays_are_unrolled_with_indices():
    layout = flatten(message_types(Middleware.ROS2), "geometry_msgs/PoseWithCovariance")
    paths = [f.path for f in layout.fields]
    assert paths[:3] == ["pose.position.x", "pose.position.y", "pose.position.z"]
    assert paths[-36:] == [f"covariance[{i}]" for i in range(36)]
    assert layout.fixed_size == 4 + 7 * 8 + 36 * 8


def test_sequence_of_messages_is_one_entry_with_an_element_layout():
    layout = flatten(message_types(Middleware.ROS2), "tf2_msgs/TFMessage")
    (transforms,) = layout.fields
    assert transforms.ros_type == "geometry_msgs/msg/TransformStamped[]"
    assert (transforms.offset, transforms.bits) == (4, None)
    element = transforms.element
    assert element.is_element
    assert element.fixed_size is None
    assert [f.path for f in element.fields][:4] == [
        "header.stamp.sec",
        "header.stamp.nanosec",
        "header.frame_id",
        "child_frame_id",
    ]
    assert all(f.offset is None for f in element.fields)
    assert element.field("transform.translation.x").align == 8


def test_ros1_sequence_type_uses_ros1_spelling():
    layout = flatten(message_types(Middleware.ROS1), "nav_msgs/Path")
    assert layout.field("poses").ros_type == "geometry_msgs/PoseStamped[]"
    assert layout.display_name == "nav_msgs/Path"


def test_sequence_of_strings_and_bounded_types():
    types = message_types(Middleware.ROS2)
    joint_state = flatten(types, "sensor_msgs/JointState")
    assert joint_state.field("name").ros_type == "string[]"
    assert joint_state.field("name").bits == 8
    bounded = [
        (name, f.path, f.bound)
        for name in types.names()
        for f in flatten(types, name).fields
        if f.bound
    ]
    assert bounded, "the humble store has bounded strings and sequences"
    assert all(bound > 0 for _, _, bound in bounded)


def test_user_definitions_from_a_directory(examples_dir):
    types = MessageTypes(Middleware.ROS1, msg_paths=[examples_dir / "franka" / "msg"])
    layout = flatten(types, "franka_msgs/FrankaState")
    assert layout.display_name == "franka_msgs/FrankaState"
    assert layout.field("header.seq").offset == 0
    assert layout.field("q[6]").path == "q[6]"
    assert layout.field("current_errors.joint_position_limits_violation").ros_type == "bool"
    assert layout.field("O_T_EE[15]").offset is None  # after header.frame_id


def test_unknown_type_suggests_the_closest_names():
    with pytest.raises(RfcError) as excinfo:
        flatten(message_types(Middleware.ROS2), "geometry_msgs/Quaternoin")
    assert str(excinfo.value) == (
        "unknown message type 'geometry_msgs/Quaternoin' for ROS 2 humble\n"
        "  hint: did you mean 'geometry_msgs/Quaternion' or 'geometry_msgs/QuaternionStamped' "
        "or 'geometry_msgs/Point'?"
    )


def test_bare_name_suggests_the_package():
    with pytest.raises(RfcError, match="did you mean 'sensor_msgs/Image'"):
        flatten(message_types(Middleware.ROS1), "Image")


def test_every_type_of_every_store_flattens():
    for middleware, distro in [
        (Middleware.ROS1, "noetic"),
        *((Middleware.ROS2, d) for d in ("foxy", "humble", "jazzy")),
    ]:
        types = message_types(middleware, distro)
        for name in types.names():
            layout = flatten(types, name)
            assert layout.fields or middleware is Middleware.ROS1, name
