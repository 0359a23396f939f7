"""The reference codec against its oracle, rosbags, on every type of the ROS 1 and ROS 2 stores."""

from __future__ import annotations

import struct

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rfc.messages.codec import FrameError, decode, default_values, encode
from rfc.messages.layout import FieldKind, flatten
from rfc.messages.rosbags_adapter import PRIMITIVE_DTYPES, Middleware, message_types
from rfc.messages.values import message_to_values, values_to_message
from tests.support.values import layout_values, same

STORES = [(Middleware.ROS1, "noetic"), (Middleware.ROS2, "humble")]
EVERY_TYPE = [
    pytest.param(middleware, distro, name, id=f"{distro}:{name}")
    for middleware, distro in STORES
    for name in message_types(middleware, distro).names()
]


@pytest.mark.parametrize(("middleware", "distro", "type_name"), EVERY_TYPE)
@settings(max_examples=12)
@given(data=st.data())
def test_codec_agrees_with_rosbags(middleware, distro, type_name, data):
    types = message_types(middleware, distro)
    layout = flatten(types, type_name)
    values = data.draw(layout_values(layout), label="values")
    message = values_to_message(values, layout, types)
    expected = types.serialize(message, type_name)

    assert encode(layout, values) == expected
    assert_static_layout_holds(layout, values, expected)
    decoded = decode(layout, expected)
    assert same(decoded, message_to_values(types.deserialize(expected, type_name), layout))
    assert same(decoded, values)


def assert_static_layout_holds(layout, values, frame):
    """Every static offset points at its field's bytes in rosbags' frame; static sizes hold."""
    if layout.fixed_size is not None:
        assert len(frame) == layout.fixed_size
    for field in layout.fields:
        if field.offset is None:
            continue
        if field.kind is FieldKind.PRIMITIVE:
            dtype = PRIMITIVE_DTYPES[field.element_type]
            stored = frame[field.offset : field.offset + dtype.itemsize]
            assert stored == np.asarray(values[field.path], dtype=dtype).tobytes(), field.path
        else:
            (count,) = struct.unpack_from("<I", frame, field.offset)
            value = values[field.path]
            expected = len(value.encode()) if isinstance(value, str) else len(value)
            terminator = layout.is_cdr and field.kind is FieldKind.STRING
            assert count == expected + terminator, field.path


@pytest.mark.parametrize(("middleware", "distro", "type_name"), EVERY_TYPE)
def test_defaults_are_what_rosbags_builds_from_zeros(middleware, distro, type_name):
    types = message_types(middleware, distro)
    layout = flatten(types, type_name)
    frame = encode(layout, default_values(layout))
    assert frame == types.serialize(
        values_to_message(default_values(layout), layout, types), type_name
    )
    if layout.fixed_size is not None:
        assert len(frame) == layout.fixed_size


def _image():
    types = message_types(Middleware.ROS2)
    layout = flatten(types, "sensor_msgs/Image")
    values = default_values(layout) | {"header.frame_id": "camera", "encoding": "mono8"}
    return layout, values


def test_truncated_frame_is_rejected():
    layout, values = _image()
    frame = encode(layout, values)
    for cut in range(len(frame)):
        with pytest.raises(FrameError) as excinfo:
            decode(layout, frame[:cut])
        assert excinfo.value.reason in {"truncated", "string"}


def test_cdr_padding_to_four_bytes_is_accepted_but_more_is_trailing():
    layout = flatten(message_types(Middleware.ROS2), "std_msgs/String")
    values = {"data": "ab"}
    frame = encode(layout, values)
    assert len(frame) % 4 == 3
    assert same(decode(layout, frame + b"\xaa"), values)
    with pytest.raises(FrameError, match="trailing"):
        decode(layout, frame + b"\xaa" * 2)


def test_ros1_frame_has_no_padding():
    types = message_types(Middleware.ROS1)
    layout = flatten(types, "geometry_msgs/Point")
    frame = encode(layout, default_values(layout))
    with pytest.raises(FrameError, match="trailing"):
        decode(layout, frame + b"\x00")


def test_big_endian_cdr_is_refused():
    layout, values = _image()
    frame = encode(layout, values)
    with pytest.raises(FrameError, match="encapsulation"):
        decode(layout, b"\x00\x00" + frame[2:])


def test_cdr_string_without_terminator_is_refused():
    types = message_types(Middleware.ROS2)
    layout = flatten(types, "std_msgs/String")
    frame = bytearray(encode(layout, {"data": "abc"}))
    frame[-1] = ord("d")
    with pytest.raises(FrameError, match="NUL"):
        decode(layout, bytes(frame))


def test_bounded_string_longer_than_its_bound_is_refused():
    types = message_types(Middleware.ROS2)
    bounded = [
        (name, field)
        for name in types.names()
        for field in flatten(types, name).fields
        if field.kind.value == "string" and field.bound
    ]
    name, field = bounded[0]
    layout = flatten(types, name)
    frame = encode(layout, default_values(layout) | {field.path: "x" * (field.bound + 1)})
    with pytest.raises(FrameError, match="bound"):
        decode(layout, frame)
