"""Robot states for the forward-kinematics example, as franka_ros publishes them.

Usage: ``python make_bags.py OUT.bag|OUT.mcap [N]`` writes N (default 20) FrankaState
messages on /franka_state_controller/franka_states: joint positions drawn within the Panda's
limits, q_d a little off q, a random flange-to-end-effector transform, and O_T_EE / O_T_EE_d
the end effector those give (NumPy) with a little noise, as a real arm reports them.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from reference import Q_MAX, Q_MIN, column_major, joint_transforms

from rfc.messages.rosbags_adapter import message_types, write_bag

TOPIC = "/franka_state_controller/franka_states"
STATE = "franka_msgs/msg/FrankaState"
MSG_PATHS = (str(Path(__file__).resolve().parent.parent / "franka" / "msg"),)


def random_transform(rng: np.random.Generator) -> np.ndarray:
    """A rotation about a random axis and a small offset, 4x4."""
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    angle = rng.uniform(-np.pi, np.pi)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    out = np.eye(4)
    out[:3, :3] = np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k
    out[:3, 3] = rng.uniform(-0.1, 0.1, size=3)
    return out


def states(count: int, seed: int = 7) -> list[dict]:
    """`count` robot states as message trees (the selected fields; the rest at defaults)."""
    rng = np.random.default_rng(seed)
    trees = []
    for index in range(count):
        q = rng.uniform(Q_MIN, Q_MAX)
        q_d = np.clip(q + rng.normal(scale=0.01, size=7), Q_MIN, Q_MAX)
        f_t_ee = column_major(random_transform(rng))
        trees.append(
            {
                "header": {
                    "seq": index,
                    "stamp": {"sec": 1000 + index, "nanosec": 500},
                    "frame_id": "panda_link0",
                },
                "q": q,
                "q_d": q_d,
                "F_T_EE": f_t_ee,
                "O_T_EE": _end_effector(q, f_t_ee) + rng.normal(scale=1e-4, size=16),
                "O_T_EE_d": _end_effector(q_d, f_t_ee) + rng.normal(scale=1e-4, size=16),
            }
        )
    return trees


def _end_effector(q: np.ndarray, f_t_ee: np.ndarray) -> np.ndarray:
    """T7 · T_flange · F_T_EE, column-major."""
    flange = np.eye(4)
    flange[2, 3] = 0.107
    end = joint_transforms(q)[6] @ flange @ np.swapaxes(f_t_ee.reshape(4, 4), 0, 1)
    return column_major(end)


def main(path: str, count: int = 20) -> None:
    """Write the bag; its suffix chooses ROS 1 (.bag) or ROS 2 (.mcap)."""
    middleware = "ros1" if path.endswith(".bag") else "ros2"
    types = message_types(middleware, msg_paths=MSG_PATHS)
    messages = []
    for index, tree in enumerate(states(count)):
        if middleware == "ros2":
            del tree["header"]["seq"]
        data = types.serialize(types.build(STATE, tree), STATE)
        messages.append((TOPIC, 1_000_000 * (index + 1), data))
    write_bag(path, types, {TOPIC: STATE}, messages)


if __name__ == "__main__":
    main(sys.argv[1], *map(int, sys.argv[2:]))
