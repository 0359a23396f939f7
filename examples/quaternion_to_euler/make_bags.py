"""Input bags for the quaternion example: random unit quaternions, or the orientations of /odom.

    python make_bags.py random 1000 quaternions.mcap [--seed 7]
    python make_bags.py odom ../../../shared/data/bags/nav2_turtlebot.mcap odom.mcap

Both write geometry_msgs/Quaternion messages on /imu/orientation, the topic project.yaml
subscribes to, 1.5 µs apart (random: just slower than the accelerator takes them, so a
simulation is all work) or at the /odom time stamps.
"""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag

TOPIC = "/imu/orientation"
QUATERNION = "geometry_msgs/msg/Quaternion"


def random_quaternions(count: int, seed: int) -> np.ndarray:
    """Uniform random unit quaternions (x, y, z, w), plus the gimbal-lock corners."""
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(count, 4))
    corners = np.array([[0, np.sqrt(0.5), 0, np.sqrt(0.5)], [0, -np.sqrt(0.5), 0, np.sqrt(0.5)]])
    q[: len(corners)] = corners[: min(count, len(corners))]
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def odom_quaternions(bag: Path) -> Iterator[tuple[int, tuple[float, float, float, float]]]:
    """Time stamp and orientation of every /odom message of a ROS 2 bag."""
    types = message_types("ros2", bags=(bag,))
    for message in read_bag(bag, types, ["/odom"]):
        odometry = types.deserialize(message.data, message.type_name)
        o = odometry.pose.pose.orientation
        yield message.timestamp_ns, (o.x, o.y, o.z, o.w)


def write_quaternions(out: Path, stamped: Iterator[tuple[int, tuple[float, ...]]]) -> int:
    """Write (time stamp, (x, y, z, w)) as Quaternion messages; return how many."""
    types = message_types("ros2")
    messages = [
        (
            TOPIC,
            stamp,
            types.serialize(types.build(QUATERNION, dict(zip("xyzw", q, strict=True))), QUATERNION),
        )
        for stamp, q in stamped
    ]
    write_bag(out, types, {TOPIC: QUATERNION}, messages)
    return len(messages)


def main() -> None:
    """Command line: see the module docstring."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    random = commands.add_parser("random", help="random unit quaternions")
    random.add_argument("count", type=int)
    random.add_argument("out", type=Path)
    random.add_argument("--seed", type=int, default=7)
    odom = commands.add_parser("odom", help="the orientations of /odom in a ROS 2 bag")
    odom.add_argument("bag", type=Path)
    odom.add_argument("out", type=Path)
    arguments = parser.parse_args()
    if arguments.command == "random":
        q = random_quaternions(arguments.count, arguments.seed)
        stamped = ((1500 * (i + 1), tuple(map(float, row))) for i, row in enumerate(q))
        count = write_quaternions(arguments.out, stamped)
    else:
        count = write_quaternions(arguments.out, odom_quaternions(arguments.bag))
    print(f"{count} quaternions on {TOPIC} in {arguments.out}")


if __name__ == "__main__":
    main()
