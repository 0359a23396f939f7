"""The codec on every message of the recorded bags, against rosbags."""

from __future__ import annotations

import pytest

from rfc.messages.codec import decode, encode
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import MessageTypes, Middleware, read_bag
from rfc.messages.values import message_to_values
from tests.conftest import shared_file
from tests.support.values import same


@pytest.mark.parametrize(
    ("bag", "middleware"),
    [
        ("bags/nav2_turtlebot.mcap", Middleware.ROS2),
        ("bags/cdr_test_0.mcap", Middleware.ROS2),
        ("bags/ROS_example.bag", Middleware.ROS1),
    ],
)
def test_every_message_of_a_recorded_bag(bag, middleware):
    path = shared_file(bag)
    types = MessageTypes(middleware, bags=[path])
    count = 0
    for message in read_bag(path, types):
        layout = flatten(types, message.type_name)
        decoded = decode(layout, message.data)
        reference = types.deserialize(message.data, message.type_name)
        assert same(decoded, message_to_values(reference, layout))
        # Padding bytes in recorded frames may hold garbage: compare with rosbags' own bytes.
        assert encode(layout, decoded) == types.serialize(reference, message.type_name)
        count += 1
    assert count > 0
