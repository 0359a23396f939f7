"""The message types the converters are co-simulated with, and where their messages come from.

Each case names a type and where its definition lives (a store, a bag, a .msg folder); values
come from the hypothesis strategies of `tests.support.values` and, where the shared data has
them, from recorded bags (their frames also carry DDS padding and padding garbage).
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, Phase, given, seed, settings

from rfc.messages.codec import decode, default_values
from rfc.messages.layout import Layout, flatten
from rfc.messages.rosbags_adapter import MessageTypes, Middleware, read_bag
from tests.conftest import ROOT, shared_file
from tests.support.values import layout_values

#: Size of the long strings and sequences drawn.
LONG = 12
#: ROS 1 has no tf2_msgs in rosbags' noetic store: its definition ships with the tests.
ROS1_MSGS = Path(__file__).parent / "msg"
FRANKA_MSGS = ROOT / "examples" / "franka" / "msg"


@dataclass(frozen=True)
class Case:
    """A message type of the matrix.

    Attributes:
        type_name: As ROS 2 spells it.
        bag: Shared bag with its definition (test_msgs) or recorded messages of it.
        msg_path: Folder of its .msg definition when no store has it.
        ros1_msg_path: Folder of its ROS 1 definition when the noetic store lacks it.
    """

    type_name: str
    bag: str | None = None
    msg_path: Path | None = None
    ros1_msg_path: Path | None = None

    @property
    def short(self) -> str:
        return self.type_name.rsplit("/", 1)[-1]

    def types(self, middleware: Middleware) -> MessageTypes:
        paths = [p for p in (self.msg_path,) if p]
        if middleware is Middleware.ROS1 and self.ros1_msg_path:
            paths.append(self.ros1_msg_path)
        bags = [shared_file(self.bag)] if self.bag and self.type_name.startswith("test_") else []
        return MessageTypes(middleware, msg_paths=paths, bags=bags)


CASES = (
    Case("geometry_msgs/msg/Quaternion"),
    Case("geometry_msgs/msg/Point"),
    Case("geometry_msgs/msg/Twist"),
    Case("geometry_msgs/msg/TwistStamped"),
    Case("sensor_msgs/msg/Imu"),
    Case("sensor_msgs/msg/Image"),
    Case("sensor_msgs/msg/LaserScan"),
    Case("sensor_msgs/msg/JointState"),
    Case("geometry_msgs/msg/PoseWithCovarianceStamped", bag="bags/nav2_turtlebot.mcap"),
    Case("nav_msgs/msg/Odometry", bag="bags/nav2_turtlebot.mcap"),
    Case("tf2_msgs/msg/TFMessage", bag="bags/nav2_turtlebot.mcap", ros1_msg_path=ROS1_MSGS),
    Case("test_msgs/msg/BasicTypes", bag="bags/cdr_test_0.mcap"),
    Case("test_msgs/msg/Arrays", bag="bags/cdr_test_0.mcap"),
    Case("franka_msgs/msg/FrankaState", msg_path=FRANKA_MSGS),
    Case("geometry_msgs/msg/PoseStamped", bag="bags/ROS_example.bag"),
    Case("std_msgs/msg/String"),
    Case("geometry_msgs/msg/Polygon"),
    Case("std_msgs/msg/Float64MultiArray"),
    Case("sensor_msgs/msg/PointCloud2"),
    Case("sensor_msgs/msg/NavSatFix"),
    Case("sensor_msgs/msg/Range"),
    Case("sensor_msgs/msg/CompressedImage"),
    Case("sensor_msgs/msg/MultiEchoLaserScan"),
    Case("diagnostic_msgs/msg/DiagnosticArray"),
)


def drawn_values(layout: Layout, config: str, count: int) -> list[dict[str, Any]]:
    """`count` messages from the layout's hypothesis strategy, the same for a config every run."""
    found: list[dict[str, Any]] = []

    @seed(zlib.crc32(config.encode()))
    @settings(
        max_examples=count,
        database=None,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
        deadline=None,
    )
    @given(layout_values(layout, long=LONG))
    def collect(values: dict[str, Any]) -> None:
        found.append(values)

    collect()
    return found[:count]


def recorded(
    case: Case, layout: Layout, limit: int = 2
) -> list[tuple[dict[str, Any], bytes | None]]:
    """Up to `limit` recorded messages of the case's type: values, and the frame itself when
    the bag was recorded with the layout's middleware (its padding may hold garbage)."""
    if case.bag is None:
        return []
    path = shared_file(case.bag)
    wanted = case.type_name.replace("/msg/", "/")
    recorded_in = Middleware.ROS1 if path.suffix == ".bag" else Middleware.ROS2
    source = MessageTypes(recorded_in, bags=[path])
    found = []
    for message in read_bag(path, source):
        if message.type_name.replace("/msg/", "/") != wanted:
            continue
        values = decode(flatten(source, message.type_name), message.data)
        if recorded_in is layout.middleware:
            found.append((values, message.data))
        else:
            found.append((_adapted(values, layout), None))
        if len(found) == limit:
            break
    return found


def _adapted(values: dict[str, Any], layout: Layout) -> dict[str, Any]:
    """Values recorded with one middleware, for the layout of the other (ROS 1 has header.seq)."""
    adapted = default_values(layout)
    for leaf in layout.fields:
        if leaf.path in values:
            value = values[leaf.path]
            if leaf.element is not None:
                value = [_adapted(item, leaf.element) for item in value]
            adapted[leaf.path] = value
    return adapted
