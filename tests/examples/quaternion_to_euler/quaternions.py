"""Test orientations: random unit quaternions with gimbal-lock and quadrant edges, and a bag's.

Quaternions are (x, y, z, w) rows of float64, the order of geometry_msgs/Quaternion.
"""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from rfc.messages.codec import decode
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import MessageTypes, Middleware, read_bag

#: Pitch within this of ±π/2 gets the looser tolerance (1e-5 rad instead of 1e-9).
GIMBAL_ZONE = 1e-3
#: cos(pitch) below this is gimbal lock for the test: the usual formulas then take roll and yaw
#: from two numbers made of rounding noise (NumPy's own angles stop reproducing the rotation),
#: so only pitch is compared there.
LOCKED = 1e-10


def from_euler(roll, pitch, yaw) -> NDArray[np.float64]:
    """Unit quaternions (x, y, z, w) of intrinsic Z-Y-X angles."""
    cr, sr = np.cos(np.asarray(roll) / 2), np.sin(np.asarray(roll) / 2)
    cp, sp = np.cos(np.asarray(pitch) / 2), np.sin(np.asarray(pitch) / 2)
    cy, sy = np.cos(np.asarray(yaw) / 2), np.sin(np.asarray(yaw) / 2)
    return np.stack(
        [
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy,
        ],
        axis=-1,
    )


def uniform(count: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """Unit quaternions uniform over rotations (normalized 4-D Gaussians)."""
    q = rng.normal(size=(count, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def gimbal_neighbourhood(count: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """Pitch between 1e-7 and 1e-3 rad away from ±π/2 (log-uniform), any roll and yaw."""
    distance = 10.0 ** rng.uniform(-7, -3, count)
    pitch = rng.choice([-1.0, 1.0], count) * (np.pi / 2 - distance)
    return from_euler(rng.uniform(-np.pi, np.pi, count), pitch, rng.uniform(-np.pi, np.pi, count))


def edges() -> NDArray[np.float64]:
    """Signs and quadrant edges: axis turns, ±π wrap-arounds, exact gimbal lock, signed zeros."""
    s = np.sqrt(0.5)
    turns = [
        [0.0, 0.0, 0.0, 1.0], [-0.0, 0.0, -0.0, 1.0], [0.0, 0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0],
        [s, 0.0, 0.0, s], [-s, 0.0, 0.0, s], [0.0, s, 0.0, s], [0.0, -s, 0.0, s],
        [0.0, 0.0, s, s], [0.0, 0.0, -s, s], [s, 0.0, 0.0, -s], [0.0, 0.0, s, -s],
        [0.5, 0.5, 0.5, 0.5], [-0.5, 0.5, -0.5, 0.5], [0.5, -0.5, 0.5, 0.5],
    ]  # fmt: skip
    tiny = [1e-300, 1e-17, 1e-9]
    near_pi = [np.pi - t for t in tiny] + [-(np.pi - t) for t in tiny] + [np.pi, -np.pi]
    angles = []
    for near in near_pi:
        angles += [(near, 0.3, 0.2), (0.1, -0.4, near), (near, 0.0, near)]
    for quarter in (np.pi / 2, -np.pi / 2):
        angles += [(quarter, 0.0, 0.0), (0.0, 0.0, quarter), (0.7, quarter, -0.3)]
    rows = np.concatenate([np.array(turns), from_euler(*np.array(angles).T)])
    return np.concatenate([rows, -rows])


def orientation_set(seed: int = 2024) -> NDArray[np.float64]:
    """1,000 orientations: 850 uniform, 100 next to gimbal lock, and the edges."""
    rng = np.random.default_rng(seed)
    special = np.concatenate([gimbal_neighbourhood(100, rng), edges()])
    return np.concatenate([uniform(1000 - len(special), rng), special])


def odom_orientations(bag: Path) -> NDArray[np.float64]:
    """pose.pose.orientation of every /odom message (nav_msgs/Odometry) in a ROS 2 bag."""
    types = MessageTypes(Middleware.ROS2, bags=[bag])
    rows = []
    for message in read_bag(bag, types, topics=["/odom"]):
        values = decode(flatten(types, message.type_name), message.data)
        rows.append([values[f"pose.pose.orientation.{axis}"] for axis in "xyzw"])
    return np.array(rows, dtype=np.float64)


def distinct(quaternions: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rows with distinct bit patterns, in first-seen order (the core keeps no state between)."""
    _, first = np.unique(quaternions.view(np.uint64), axis=0, return_index=True)
    return quaternions[np.sort(first)]


def angle_error(got: NDArray[np.float64], want: NDArray[np.float64]) -> NDArray[np.float64]:
    """|got - want| on the circle: -π and π are the same angle."""
    return np.abs(np.remainder(got - want + np.pi, 2 * np.pi) - np.pi)


def tolerance(numpy_angles: NDArray[np.float64]) -> NDArray[np.float64]:
    """The bound per row: 1e-9 rad, 1e-5 rad when pitch is within 1e-3 of ±π/2."""
    near_lock = np.abs(numpy_angles[:, 1]) > np.pi / 2 - GIMBAL_ZONE
    return np.where(near_lock, 1e-5, 1e-9)


def rotation(quaternions: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation matrices of unit quaternions (x, y, z, w)."""
    x, y, z, w = quaternions.T
    return np.stack(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    ).transpose(2, 0, 1)


def exact_cos_pitch(quaternions: NDArray[np.float64]) -> NDArray[np.float64]:
    """cos(pitch) = |(1 - 2(x² + y²), 2(wx + yz))|, with the two terms in exact arithmetic."""
    lengths = []
    for row in quaternions:
        x, y, z, w = (Fraction(float(c)) for c in row)
        lengths.append(np.hypot(float(1 - 2 * (x * x + y * y)), float(2 * (w * x + y * z))))
    return np.array(lengths)


def check_against_numpy(angles: NDArray[np.float64], quaternions: NDArray[np.float64], numpy_ref):
    """Assert the issue's accuracy: within tolerance of NumPy, and the quaternion's rotation.

    At gimbal lock only pitch is compared (see `LOCKED`).
    """
    want = numpy_ref(quaternions)
    error = angle_error(angles, want)
    bound = tolerance(want)
    locked = exact_cos_pitch(quaternions) < LOCKED
    error[locked, 0] = error[locked, 2] = 0.0
    worst = np.argmax((error / bound[:, None]).max(axis=1))
    assert (error <= bound[:, None]).all(), (
        f"{int((error > bound[:, None]).any(axis=1).sum())} orientations off; worst: "
        f"q={quaternions[worst].tolist()} got={angles[worst].tolist()} numpy={want[worst].tolist()}"
    )
    rebuilt = rotation(from_euler(*angles[~locked].T))
    assert np.abs(rebuilt - rotation(quaternions[~locked])).max() <= 1e-5
