"""check-connections and expand-selections on systems that are right: what they infer."""

from __future__ import annotations

import pytest

from rfc.ir.fields import selected_paths
from tests.passes.specs import compile_yaml, pass_through

FAN_OUT = """\
project: {name: P}
accelerators:
  - name: Mix
    type: HLS
    sources: ./accel.cpp
    interface:
      input: [{name: rot, message: geometry_msgs/Quaternion},
              {name: pos, message: geometry_msgs/Point, include: [x]}]
      output: [{name: mixed, message: geometry_msgs/Point}]
blocks:
  - {name: Rot_sub, type: ROS>accelerator, message: geometry_msgs/Quaternion,
     outgoing: [{name: Mix_a}, {name: Mix_b}]}
  - {name: Pos_sub, type: ROS>accelerator, message: geometry_msgs/Point,
     outgoing: [{name: Mix_a, include: [x, y]}, {name: Mix_b, exclude: [z]}]}
  - {name: Mix_a, type: Mix, outgoing: [{name: A_pub}]}
  - {name: Mix_b, type: Mix, outgoing: [{name: B_pub, include: [z]}]}
  - {name: A_pub, type: accelerator>ROS, message: geometry_msgs/Point}
  - {name: B_pub, type: accelerator>ROS, message: geometry_msgs/Point}
"""


def test_fan_out_and_port_inference_by_message_type(tmp_path):
    design = compile_yaml(tmp_path, FAN_OUT)
    assert [(str(c.source), str(c.destination), c.fields) for c in design.connections] == [
        ("Rot_sub.out0", "Mix_a.rot", ("x", "y", "z", "w")),
        ("Rot_sub.out0", "Mix_b.rot", ("x", "y", "z", "w")),
        ("Pos_sub.out0", "Mix_a.pos", ("x",)),  # the port needs only x
        ("Pos_sub.out0", "Mix_b.pos", ("x",)),
        ("Mix_a.mixed", "A_pub.in0", ("x", "y", "z")),
        ("Mix_b.mixed", "B_pub.in0", ("z",)),
    ]


def test_output_ports_select_the_union_of_what_they_send(tmp_path):
    design = compile_yaml(tmp_path, FAN_OUT)
    assert tuple(selected_paths(design.block("Pos_sub").port("out0").layout)) == ("x",)
    assert tuple(selected_paths(design.block("B_pub").port("in0").layout)) == ("z",)
    (_, b_pub) = design.infrastructure.publishers
    assert [f.selected for f in b_pub.layout.fields] == [False, False, True]


@pytest.mark.parametrize(
    ("message", "include", "fields"),
    [
        (
            "sensor_msgs/Image",
            "header",
            ("header.stamp.sec", "header.stamp.nanosec", "header.frame_id"),
        ),
        (
            "sensor_msgs/Image",
            "'header.*', data",
            ("header.stamp.sec", "header.stamp.nanosec", "header.frame_id", "data"),
        ),
        (
            "geometry_msgs/PoseWithCovariance",
            "'pose.orientation.*', 'covariance[3]'",
            (
                "pose.orientation.x",
                "pose.orientation.y",
                "pose.orientation.z",
                "pose.orientation.w",
                "covariance[3]",
            ),
        ),
    ],
)
def test_include_hints_expand_to_every_leaf(tmp_path, message, include, fields):
    design = compile_yaml(tmp_path, pass_through(message, include=include))
    assert design.connections[1].fields == fields


def test_sequence_element_fields_expand_through_the_sequence(tmp_path):
    text = pass_through("tf2_msgs/TFMessage", include="transforms.child_frame_id")
    assert compile_yaml(tmp_path, text).connections[1].fields == ("transforms.child_frame_id",)


def test_direct_subscriber_to_publisher_loopback_is_a_system(tmp_path):
    text = """\
project: {name: Echo}
blocks:
  - {name: In_sub, type: ROS>accelerator, message: sensor_msgs/Image,
     outgoing: [{name: Out_pub}]}
  - {name: Out_pub, type: accelerator>ROS, message: sensor_msgs/Image}
"""
    design = compile_yaml(tmp_path, text)
    assert len(design.connections[0].fields) == 9
