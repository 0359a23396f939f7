"""NumPy float64 reference of the forward-kinematics accelerator (the oracle of its tests).

The Panda's kinematics with Franka's published modified (Craig) Denavit-Hartenberg
parameters: frame i follows frame i - 1 by ``RotX(alpha) · TransX(a) · RotZ(q) · TransZ(d)``,
and the flange sits 0.107 m along the last frame's z axis. Transforms travel as 16 values,
column-major, like franka_msgs' ``O_T_EE``.
"""

from __future__ import annotations

import numpy as np

A = (0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088)
D = (0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0)
ALPHA = (0.0, -np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, np.pi / 2, np.pi / 2)
FLANGE = 0.107
#: Joint position limits (rad), from Franka's robot specifications.
Q_MIN = (-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973)
Q_MAX = (2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973)


def _rot_x(angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(c), np.zeros_like(c)
    rows = [[one, zero, zero, zero], [zero, c, -s, zero], [zero, s, c, zero]]
    return np.stack([np.stack(r, -1) for r in [*rows, [zero, zero, zero, one]]], -2)


def _rot_z(angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(c), np.zeros_like(c)
    rows = [[c, -s, zero, zero], [s, c, zero, zero], [zero, zero, one, zero]]
    return np.stack([np.stack(r, -1) for r in [*rows, [zero, zero, zero, one]]], -2)


def _translate(x: float, y: float, z: float) -> np.ndarray:
    out = np.eye(4)
    out[:3, 3] = (x, y, z)
    return out


def joint_transforms(q: np.ndarray) -> np.ndarray:
    """T1…T7 (base to joint i) for joint positions `q` of shape (..., 7): (..., 7, 4, 4)."""
    q = np.asarray(q, dtype=np.float64)
    frame = np.broadcast_to(np.eye(4), (*q.shape[:-1], 4, 4))
    out = []
    for i in range(7):
        step = _rot_x(np.full(q.shape[:-1], ALPHA[i])) @ _translate(A[i], 0, 0)
        frame = frame @ step @ _rot_z(q[..., i]) @ _translate(0, 0, D[i])
        out.append(frame)
    return np.stack(out, -3)


def column_major(transform: np.ndarray) -> np.ndarray:
    """4x4 matrices (..., 4, 4) as franka sends them: (..., 16), column by column."""
    return np.swapaxes(transform, -1, -2).reshape(*transform.shape[:-2], 16)


def from_column_major(values: np.ndarray) -> np.ndarray:
    """The inverse of `column_major`."""
    return np.swapaxes(np.asarray(values, dtype=np.float64).reshape(-1, 4, 4), -1, -2)


def forward_kinematics(
    q: np.ndarray, f_t_ee: np.ndarray, o_t_ee: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The accelerator's outputs for a batch: transforms (n, 112) and mse (n,).

    Args:
        q: Joint positions, (n, 7).
        f_t_ee: Flange-to-end-effector transforms, column-major, (n, 16).
        o_t_ee: The measured base-to-end-effector transforms, column-major, (n, 16).

    Returns:
        T1…T7 column-major one after the other, and the mean over the 16 entries of
        (T7 · T_flange · F_T_EE - O_T_EE)².
    """
    frames = joint_transforms(np.atleast_2d(q))
    end = frames[:, 6] @ _translate(0, 0, FLANGE) @ from_column_major(f_t_ee)
    error = end - from_column_major(o_t_ee)
    mse = np.mean(error.reshape(-1, 16) ** 2, axis=1)
    return column_major(frames).reshape(-1, 112), mse
