"""The same converter blocks in MyHDL's own simulator (a representative subset of the matrix).

GHDL co-simulation (tests/hdl/converters) covers every type, width and middleware; here the
MyHDL blocks themselves run — fixed fields, strings, primitive sequences, sequences of strings
and of messages, each width and both middlewares — with random idle and backpressure on every
handshake, held to the reference codec (itself byte-exact with rosbags).
"""

from __future__ import annotations

import pytest

from rfc.lib.converters.plan import plan
from rfc.lib.converters.transactions import transactions
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from tests.hdl.converters.matrix import drawn_values
from tests.lib.converters.myhdl_bench import simulate_publisher, simulate_subscriber, visible

#: Room for the drawn messages: their strings take up to 4 bytes a character.
LIMITS = Limits(string=255, sequence=16, frame=2048)

SUBSET = [
    ("geometry_msgs/msg/Quaternion", Middleware.ROS2, 8),
    ("geometry_msgs/msg/TwistStamped", Middleware.ROS1, 64),
    ("sensor_msgs/msg/Imu", Middleware.ROS1, 32),
    ("sensor_msgs/msg/JointState", Middleware.ROS2, 64),
    ("sensor_msgs/msg/Image", Middleware.ROS2, 32),
    ("tf2_msgs/msg/TFMessage", Middleware.ROS2, 8),
]


@pytest.mark.slow
@pytest.mark.parametrize(
    ("type_name", "middleware", "width"),
    SUBSET,
    ids=[f"{t.rsplit('/', 1)[-1]}-{m.value}-{w}" for t, m, w in SUBSET],
)
def test_myhdl_simulation_agrees_with_the_reference_codec(type_name, middleware, width):
    layout = flatten(message_types(middleware), type_name)
    converters = plan(layout, width, LIMITS)
    values = drawn_values(layout, f"myhdl {type_name} {middleware.value} {width}", 3)
    frames = [encode(layout, v) for v in values]

    parsed = simulate_subscriber(converters, frames, seed=width)
    assert [p.error for p in parsed] == [False] * len(frames)
    assert [p.message for p in parsed] == [visible(transactions(converters, v)) for v in values]

    sent = simulate_publisher(converters, [transactions(converters, v) for v in values], seed=width)
    assert sent == [(frame, len(frame)) for frame in frames]


def test_a_truncated_frame_is_flagged_and_the_next_one_still_decoded():
    layout = flatten(message_types(Middleware.ROS2), "sensor_msgs/msg/JointState")
    converters = plan(layout, 32, LIMITS)
    values = drawn_values(layout, "myhdl truncated JointState", 2)
    good = [encode(layout, v) for v in values]
    parsed = simulate_subscriber(converters, [good[0][:-5], good[1]], seed=3)
    assert [p.error for p in parsed] == [True, False]
    assert parsed[1].message == visible(transactions(converters, values[1]))
