"""derive-infrastructure: ids, frame sizes (held to rosbags), frame-length circuits, buffers."""

from __future__ import annotations

import math

import pytest

from rfc.ir.infrastructure import CHUNK_HEADER_BYTES, DmaDirection
from rfc.messages.codec import default_values
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import message_types
from rfc.messages.values import values_to_message
from rfc.passes.frame_size import frame_bound
from tests.passes.specs import compile_yaml, pass_through


def rosbags_default_frame(middleware, message):
    """Bytes rosbags serializes for the message with every field at its default."""
    types = message_types(middleware)
    layout = flatten(types, message)
    return len(
        types.serialize(values_to_message(default_values(layout), layout, types), layout.type_name)
    )


@pytest.mark.parametrize("middleware", ["ROS", "ROS2"])
@pytest.mark.parametrize("message", ["geometry_msgs/Point", "geometry_msgs/PoseWithCovariance"])
def test_static_frames_are_exact(tmp_path, middleware, message):
    design = compile_yaml(tmp_path, pass_through(message, middleware=middleware))
    infrastructure = design.infrastructure
    (subscriber,), (publisher,) = infrastructure.subscribers, infrastructure.publishers
    wire = "ros1" if middleware == "ROS" else "ros2"
    assert subscriber.frame_bytes == publisher.frame_bytes == rosbags_default_frame(wire, message)
    assert not publisher.needs_frame_length


@pytest.mark.parametrize("width", [8, 32, 64])
def test_transfer_beats_include_the_chunk_header(tmp_path, width):
    design = compile_yaml(tmp_path, pass_through("geometry_msgs/Point", width=width))
    (scheduler_input,) = design.infrastructure.scheduler.inputs
    assert scheduler_input.transfer_exact
    assert scheduler_input.transfer_beats == math.ceil((CHUNK_HEADER_BYTES + 28) / (width // 8))


def test_image_publisher_needs_a_frame_length_circuit_fed_by_its_variable_fields(tmp_path):
    design = compile_yaml(tmp_path, pass_through("sensor_msgs/Image"))
    (publisher,) = design.infrastructure.publishers
    assert publisher.needs_frame_length
    assert publisher.frame_bytes is None
    assert publisher.length_fields == ("header.frame_id", "encoding", "data")
    assert design.infrastructure.buffers == ()  # the paper: Image needs no buffering
    (scheduler_input,) = design.infrastructure.scheduler.inputs
    assert not scheduler_input.transfer_exact


def test_publisher_without_variable_fields_selected_has_a_static_frame(tmp_path):
    text = pass_through("sensor_msgs/Image", include="height, width, step")
    (publisher,) = compile_yaml(tmp_path, text).infrastructure.publishers
    assert not publisher.needs_frame_length
    # unselected strings and sequences go out empty: the default message's size
    assert publisher.frame_bytes == rosbags_default_frame("ros2", "sensor_msgs/Image")


def test_sequences_with_variable_elements_are_buffered(tmp_path):
    design = compile_yaml(tmp_path, pass_through("tf2_msgs/TFMessage"))
    (publisher,) = design.infrastructure.publishers
    assert publisher.length_fields == ("transforms",)
    assert [(b.publisher, b.field) for b in design.infrastructure.buffers] == [
        ("Pub", "transforms")
    ]


def test_ids_count_subscribers_and_publishers_apart_in_spec_order(tmp_path):
    text = """\
project: {name: P}
accelerators:
  - name: Fuse
    type: HLS
    sources: ./accel.cpp
    interface:
      input: [{name: a, message: geometry_msgs/Point}, {name: b, message: geometry_msgs/Point}]
      output: [{name: sum, message: geometry_msgs/Point},
               {name: diff, message: geometry_msgs/Point}]
blocks:
  - {name: A_sub, type: ROS>accelerator, message: geometry_msgs/Point,
     outgoing: [{name: Fuse_acc, port: a}]}
  - {name: Diff_pub, type: accelerator>ROS, message: geometry_msgs/Point, period: 500}
  - {name: B_sub, type: ROS>accelerator, message: geometry_msgs/Point,
     outgoing: [{name: Fuse_acc, port: b}]}
  - {name: Fuse_acc, type: Fuse, outgoing: [{name: Sum_pub, from: sum},
                                             {name: Diff_pub, from: diff}]}
  - {name: Sum_pub, type: accelerator>ROS, message: geometry_msgs/Point, deadline: 100}
"""
    infrastructure = compile_yaml(tmp_path, text).infrastructure
    assert [(c.id, c.block) for c in infrastructure.subscribers] == [(0, "A_sub"), (1, "B_sub")]
    assert [(c.id, c.block) for c in infrastructure.publishers] == [(0, "Diff_pub"), (1, "Sum_pub")]
    assert [
        (i.index, i.publisher, i.period, i.deadline) for i in infrastructure.scheduler.inputs
    ] == [
        (0, "Diff_pub", 500, 500),  # implicit deadline: the period
        (1, "Sum_pub", None, 100),
    ]
    mm2s, s2mm = infrastructure.dma
    # AXI DMA names: MM2S reads memory into the logic, S2MM writes its results back.
    assert (mm2s.name, mm2s.direction, mm2s.converters) == (
        "mm2s",
        DmaDirection.PS_TO_PL,
        ("A_sub", "B_sub"),
    )
    assert (s2mm.name, s2mm.direction, s2mm.converters) == (
        "s2mm",
        DmaDirection.PL_TO_PS,
        ("Diff_pub", "Sum_pub"),
    )


def test_frame_bound_covers_the_largest_bounded_message(tmp_path):
    package = tmp_path / "msgs" / "bounded_msgs" / "msg"
    package.mkdir(parents=True)
    (package / "Bounded.msg").write_text(
        "uint8 flag\nstring<=10 name\nfloat64[<=3] values\nstring<=4[<=2] tags\nint16 last\n"
    )
    types = message_types("ros2", None, (str(tmp_path / "msgs"),))
    layout = flatten(types, "bounded_msgs/Bounded")
    largest = {
        "flag": 1,
        "name": "x" * 10,
        "values": [1.0, 2.0, 3.0],
        "tags": ["abcd", "efgh"],
        "last": 7,
    }
    size = len(types.serialize(types.build(layout.type_name, largest), layout.type_name))
    bound = frame_bound(layout)
    assert size <= bound <= size + 16  # only alignment slack on top
    assert frame_bound(flatten(types, "sensor_msgs/Image")) is None  # unbounded


@pytest.mark.parametrize(
    ("type_name", "largest", "maxima"),
    [
        (
            "sensor_msgs/msg/JointState",
            {"header": {"stamp": {"sec": 1, "nanosec": 2}, "frame_id": "x" * 9},
             "name": ["abcdefgh", "ij"], "position": [1.0, 2.0], "velocity": [], "effort": [3.0]},
            Limits(string=9, sequence=2, fields={"name[]": 8}),
        ),
        (
            "tf2_msgs/msg/TFMessage",
            {"transforms": [
                {"header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "map"},
                 "child_frame_id": "odom",
                 "transform": {"translation": {"x": 0.0, "y": 0.0, "z": 0.0},
                               "rotation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}}}
            ] * 3},
            Limits(string=4, sequence=3),
        ),
    ],
)  # fmt: skip
def test_the_maxima_bound_an_unbounded_frame(type_name, largest, maxima):
    """The largest message the maxima allow fits in the bound, with only alignment slack."""
    types = message_types("ros2")
    layout = flatten(types, type_name)
    size = len(types.serialize(types.build(type_name, largest), type_name))
    bound = frame_bound(layout, maxima)
    assert size <= bound <= 2 * size  # alignment slack only (each field its worst padding)
    assert frame_bound(layout) is None


def test_declared_max_bytes_bounds_a_variable_frame(tmp_path):
    text = pass_through("sensor_msgs/Image", publisher=", maxBytes: 4096")
    (scheduler_input,) = compile_yaml(tmp_path, text).infrastructure.scheduler.inputs
    assert scheduler_input.transfer_beats == math.ceil((CHUNK_HEADER_BYTES + 4096) / 8)
