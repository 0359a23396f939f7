"""The accelerator-side and DMA-side port contract (docs/converters.md), and generation.

Issue 7's wrappers and accelerators are written against these names: they come from dotted
paths, mirror between subscriber and publisher, and are what the generated entity declares.
"""

from __future__ import annotations

import pytest

from rfc.errors import RfcError
from rfc.lib.converters.build import generate
from rfc.lib.converters.plan import accelerator_ports, plan
from rfc.lib.converters.ports import Direction, PortRole, Side, dma_ports
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import select
from rfc.toolchain import read_entities

LIMITS = Limits(string=16, sequence=8, frame=1024)


def layout_of(type_name, middleware=Middleware.ROS2):
    return flatten(message_types(middleware), type_name)


def names(ports):
    return [p.name for p in ports]


def test_fixed_fields_are_named_by_their_paths_with_a_message_handshake():
    ports = accelerator_ports(layout_of("geometry_msgs/msg/Quaternion"), 8)
    assert [(p.name, p.bits, p.direction, p.role) for p in ports] == [
        ("msg_valid", 1, Direction.OUT, PortRole.VALID),
        ("msg_ready", 1, Direction.IN, PortRole.READY),
        ("msg_error", 1, Direction.OUT, PortRole.ERROR),
        ("x", 64, Direction.OUT, PortRole.FIELD),
        ("y", 64, Direction.OUT, PortRole.FIELD),
        ("z", 64, Direction.OUT, PortRole.FIELD),
        ("w", 64, Direction.OUT, PortRole.FIELD),
    ]


def test_nested_fields_and_array_elements_join_their_path_with_underscores():
    found = names(accelerator_ports(layout_of("geometry_msgs/msg/PoseWithCovarianceStamped"), 64))
    assert {"header_stamp_sec", "pose_pose_position_x", "pose_covariance_0"} <= set(found)
    assert found[-1] == "pose_covariance_35"


def test_strings_and_sequences_are_sub_streams_with_their_lengths():
    ports = {
        p.name: p for p in accelerator_ports(layout_of("sensor_msgs/msg/Image"), 32, limits=LIMITS)
    }
    assert ports["encoding_length"].role is PortRole.LENGTH
    assert ports["data_length"].role is PortRole.COUNT
    for stream in ("header_frame_id", "encoding", "data"):
        assert ports[f"{stream}_tdata"].bits == 32
        assert ports[f"{stream}_tkeep"].bits == 4
        assert ports[f"{stream}_tready"].direction is Direction.IN
        assert {f"{stream}_tvalid", f"{stream}_tlast"} <= set(ports)
    # The length port is as wide as the configured maximum needs (16 characters: 5 bits).
    assert ports["encoding_length"].bits == 5


def test_sequences_of_messages_are_element_streams():
    ports = {
        p.name: p for p in accelerator_ports(layout_of("tf2_msgs/msg/TFMessage"), 64, limits=LIMITS)
    }
    assert ports["transforms_length"].role is PortRole.COUNT
    for handshake in ("transforms_valid", "transforms_ready", "transforms_last"):
        assert ports[handshake].group == "transforms"
    assert ports["transforms_transform_rotation_w"].group == "transforms"
    assert ports["transforms_child_frame_id_tdata"].group == "transforms_child_frame_id"


@pytest.mark.parametrize(
    "type_name", ["sensor_msgs/msg/JointState", "tf2_msgs/msg/TFMessage", "sensor_msgs/msg/Imu"]
)
def test_publisher_ports_mirror_the_subscriber_so_one_wires_to_the_other(type_name):
    layout = layout_of(type_name)
    sub = accelerator_ports(layout, 32, Side.SUBSCRIBER, LIMITS)
    pub = {p.name: p for p in accelerator_ports(layout, 32, Side.PUBLISHER, LIMITS)}
    # The publisher takes lengths on its length ports, so it needs no tkeep/tlast/last; only
    # the subscriber judges frames (msg_error). Everything else is the same port, mirrored.
    only_subscriber = {PortRole.ERROR, PortRole.TKEEP, PortRole.TLAST, PortRole.LAST}
    for port in sub:
        if port.role in only_subscriber:
            assert port.name not in pub
            continue
        mirrored = pub.pop(port.name)
        assert (mirrored.bits, mirrored.role) == (port.bits, port.role)
        assert mirrored.direction is not port.direction
    assert pub == {}


def test_excluded_fields_have_no_ports():
    layout = select(layout_of("sensor_msgs/msg/Imu"), (), ("*covariance*", "header.*"))
    found = names(accelerator_ports(layout, 64))
    assert "orientation_w" in found
    assert not [n for n in found if "covariance" in n or n.startswith("header")]


def test_dma_side_is_one_axi_stream_per_direction_with_status():
    layout = layout_of("sensor_msgs/msg/Image")
    converters = plan(layout, 64, LIMITS)
    assert names(dma_ports(converters, Side.SUBSCRIBER)) == [
        "clk", "rst", "s_axis_tdata", "s_axis_tkeep", "s_axis_tvalid", "s_axis_tready",
        "s_axis_tlast", "error_count", "error_reason",
    ]  # fmt: skip
    assert names(dma_ports(converters, Side.PUBLISHER))[:8] == [
        "clk", "rst", "m_axis_tdata", "m_axis_tkeep", "m_axis_tvalid", "m_axis_tready",
        "m_axis_tlast", "frame_length",
    ]  # fmt: skip


def test_a_bus_width_other_than_8_32_64_is_refused():
    with pytest.raises(RfcError, match=r"bus width 16 is not supported; expected one of 8, 32, 64"):
        plan(layout_of("geometry_msgs/msg/Point"), 16)


def test_a_message_without_fields_is_refused_with_a_hint():
    with pytest.raises(RfcError, match="has no fields") as raised:
        plan(layout_of("std_msgs/msg/Empty", Middleware.ROS1), 8)
    assert raised.value.hint


@pytest.mark.parametrize("side", list(Side))
def test_generated_entity_declares_exactly_the_listed_ports(side, tmp_path):
    converters = plan(layout_of("sensor_msgs/msg/JointState"), 32, LIMITS)
    made = generate(converters, side, tmp_path, "joints_" + side.value)
    assert [f.name for f in made.files] == [
        "pck_myhdl_011.vhd",
        f"{made.name}.vhd",
        f"{made.name}.v",
    ]
    # GHDL's parser needs MyHDL's package with the entity: read them as one file.
    together = tmp_path / "together.vhd"
    together.write_text("".join(f.read_text() for f in made.vhdl))
    (entity,) = read_entities(together)
    assert entity.name == made.name
    assert [(p.name, p.mode, p.bits) for p in entity.ports] == [
        (p.name, p.direction.value, p.bits) for p in made.ports
    ]
