"""Include/exclude selections (the paper's Listing 2) and their errors."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import all_paths, select


def image():
    return flatten(message_types(Middleware.ROS2), "sensor_msgs/Image")


def chosen(layout):
    return [f.path for f in layout.fields if f.selected]


def test_no_selection_selects_everything():
    assert chosen(select(image())) == [f.path for f in image().fields]


def test_include_a_sub_message_selects_its_leaves():
    assert chosen(select(image(), include=["header.stamp", "data"])) == [
        "header.stamp.sec",
        "header.stamp.nanosec",
        "data",
    ]


def test_wildcard_matches_one_segment_and_everything_below():
    assert chosen(select(image(), include=["header.*"])) == [
        "header.stamp.sec",
        "header.stamp.nanosec",
        "header.frame_id",
    ]


def test_exclude_after_include():
    layout = select(image(), include=["header.*", "height", "width"], exclude=["header.frame_id"])
    assert chosen(layout) == ["header.stamp.sec", "header.stamp.nanosec", "height", "width"]


def test_exclude_alone_keeps_the_rest():
    assert "header.frame_id" not in chosen(select(image(), exclude=["header"]))
    assert chosen(select(image(), exclude=["header"]))[0] == "height"


def test_array_elements_by_index_and_wildcard():
    layout = flatten(message_types(Middleware.ROS2), "geometry_msgs/PoseWithCovariance")
    assert chosen(select(layout, include=["covariance[35]"])) == ["covariance[35]"]
    assert len(chosen(select(layout, include=["covariance[*]"]))) == 36
    assert len(chosen(select(layout, include=["covariance"]))) == 36


def test_prefix_is_not_a_partial_name():
    layout = flatten(message_types(Middleware.ROS2), "sensor_msgs/CameraInfo")
    assert chosen(select(layout, include=["d"])) == ["d"]


def test_selection_inside_sequence_elements():
    layout = flatten(message_types(Middleware.ROS2), "tf2_msgs/TFMessage")
    for spelling in ("transforms.child_frame_id", "transforms[].child_frame_id"):
        selected = select(layout, include=[spelling])
        (transforms,) = selected.fields
        assert transforms.selected
        assert chosen(transforms.element) == ["child_frame_id"]
    nothing = select(layout, exclude=["transforms"])
    assert not nothing.fields[0].selected


def test_missing_path_suggests_close_paths():
    with pytest.raises(RfcError) as excinfo:
        select(image(), include=["header.stamp.secs"])
    assert str(excinfo.value) == (
        "sensor_msgs/msg/Image has no field 'header.stamp.secs'\n"
        "  hint: did you mean 'header.stamp.sec' or 'header.stamp.nanosec' or 'header.stamp'?"
    )


def test_missing_path_without_near_miss_lists_top_level_fields():
    with pytest.raises(RfcError) as excinfo:
        select(image(), exclude=["zzzzzz"])
    assert "its top-level fields are header, height, width, encoding" in str(excinfo.value)


def test_all_paths_include_intermediate_messages():
    paths = all_paths(image())
    assert {"header", "header.stamp", "header.stamp.sec", "data"} <= paths
