"""The maxima a message is held to: the converters' and the runtime's shared rule.

`Limits.beyond` names the first string or sequence a decoded message holds beyond its maximum —
nested ones through their sequence, each string of a sequence of strings as ``path[]`` — the
same keys and the same counts (bytes of UTF-8 text, elements of sequences) the plans use.
"""

from __future__ import annotations

import pytest

from rfc.messages.codec import decode, encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import message_types

TYPES = message_types("ros2")


def values_of(type_name: str, message: dict) -> tuple:
    layout = flatten(TYPES, type_name)
    frame = TYPES.serialize(TYPES.build(type_name, message), type_name)
    decoded = decode(layout, frame)
    assert encode(layout, decoded) == frame  # the codec's view is rosbags'
    return layout, decoded


def joint_state(names: list[str], positions: int) -> dict:
    return {
        "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "arm"},
        "name": names,
        "position": [0.0] * positions,
        "velocity": [],
        "effort": [],
    }


def tf(frames: list[str]) -> dict:
    zero = {"x": 0.0, "y": 0.0, "z": 0.0}
    return {
        "transforms": [
            {
                "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": frame},
                "child_frame_id": "c",
                "transform": {"translation": zero, "rotation": zero | {"w": 1.0}},
            }
            for frame in frames
        ]
    }


@pytest.mark.parametrize(
    ("type_name", "message", "limits", "beyond"),
    [
        ("sensor_msgs/msg/JointState", joint_state(["a", "b"], 2), Limits(sequence=2), None),
        ("sensor_msgs/msg/JointState", joint_state(["a"], 3), Limits(sequence=2), "position"),
        ("sensor_msgs/msg/JointState", joint_state(["a"], 3),
         Limits(sequence=2, fields={"position": 3}), None),
        ("sensor_msgs/msg/JointState", joint_state(["abcd"], 1), Limits(string=3), "name[]"),
        ("sensor_msgs/msg/JointState", joint_state(["abcd"], 1),
         Limits(string=3, fields={"name[]": 4, "header.frame_id": 3}), None),
        # UTF-8 bytes, as on the wire: two characters, four bytes
        ("sensor_msgs/msg/JointState", joint_state(["éé"], 1), Limits(string=3), "name[]"),
        ("tf2_msgs/msg/TFMessage", tf(["map", "odom"]), Limits(string=4, sequence=2), None),
        ("tf2_msgs/msg/TFMessage", tf(["map", "odom"]), Limits(string=4, sequence=1),
         "transforms"),
        ("tf2_msgs/msg/TFMessage", tf(["map", "base_link"]), Limits(string=4),
         "transforms.header.frame_id"),
    ],
)  # fmt: skip
def test_beyond_names_the_first_field_over_its_maximum(type_name, message, limits, beyond):
    layout, values = values_of(type_name, message)
    assert limits.beyond(layout, values) == beyond
