"""A guard's checker gets every port of the subscriber it is, and holds exactly its inputs high.

It captures no field (`without_fields`): its verdict rests on the walk, which stays the
subscriber's.
"""

from __future__ import annotations

import pytest
from myhdl import Signal

from rfc.lib.axi_stream import STREAM
from rfc.lib.converters.checker import checker_ports, checker_signals, without_fields
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Direction, PortRole, Side, ports_of
from rfc.lib.converters.subscriber import subscriber_ports
from rfc.lib.converters.tables import tables
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import Middleware, message_types


def checked_plan(middleware, type_name):
    return plan(flatten(message_types(middleware), type_name), 8)


@pytest.mark.parametrize(
    ("middleware", "type_name"),
    [(Middleware.ROS1, "sensor_msgs/msg/JointState"), (Middleware.ROS2, "nav_msgs/msg/Path")],
)
def test_the_checker_ports_are_the_subscribers_and_its_readies_its_inputs(middleware, type_name):
    checking = checked_plan(middleware, type_name)
    checker, readies = checker_signals(checking)
    stream = tuple(Signal(bool(0)) for _ in range(5))
    cause = Signal(bool(0))

    ports = checker_ports(Signal(bool(0)), Signal(bool(0)), stream, cause, checker)

    assert list(ports) == subscriber_ports(checking)
    assert tuple(ports[f"s_axis_{n}"] for n in STREAM) == stream
    assert ports["error_reason"] is cause
    inputs = [p.name for p in ports_of(checking, Side.SUBSCRIBER) if p.direction is Direction.IN]
    assert readies == [checker[name] for name in inputs]
    assert inputs  # the consumer's readies: each channel and stream of the message


@pytest.mark.parametrize(
    ("middleware", "type_name"),
    [(Middleware.ROS1, "sensor_msgs/msg/JointState"), (Middleware.ROS2, "nav_msgs/msg/Path")],
)
def test_a_checker_captures_no_field_and_walks_as_the_subscriber(middleware, type_name):
    subscribed = checked_plan(middleware, type_name)
    checking = without_fields(subscribed)
    ports = {p.name: p.role for p in ports_of(subscribed, Side.SUBSCRIBER)}
    assert PortRole.FIELD in ports.values()  # header fields; Path's poses' fields too
    kept = {p.name: p.role for p in ports_of(checking, Side.SUBSCRIBER)}
    assert kept == {name: role for name, role in ports.items() if role is not PortRole.FIELD}
    assert tables(checking) == tables(subscribed)
