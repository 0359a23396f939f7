"""Layouts as data: what the plan carries is the layout the compiler derived, field for field."""

from __future__ import annotations

import json
from dataclasses import replace

import pytest

from rfc.messages.layout import flatten
from rfc.messages.layout_model import layout_from_json, layout_to_json
from rfc.messages.rosbags_adapter import message_types


@pytest.mark.parametrize("middleware", ["ros1", "ros2"])
@pytest.mark.parametrize(
    "type_name",
    [
        "geometry_msgs/msg/PoseWithCovarianceStamped",
        "nav_msgs/msg/Path",
        "sensor_msgs/msg/Image",
        "sensor_msgs/msg/JointState",
        "visualization_msgs/msg/MarkerArray",
    ],
)
def test_a_layout_survives_its_json_form(middleware, type_name):
    layout = flatten(message_types(middleware), type_name)
    # a selection and bounds, as a connection and the maxima leave them
    layout = layout.with_fields(
        tuple(replace(f, selected=i % 2 == 0, bound=i) for i, f in enumerate(layout.fields))
    )
    document = json.loads(json.dumps(layout_to_json(layout)))
    assert layout_from_json(document) == layout
