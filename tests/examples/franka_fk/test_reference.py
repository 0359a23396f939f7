"""The NumPy reference against what Franka publishes about the Panda."""

from __future__ import annotations

import numpy as np

from tests.examples.franka_fk.example import load, states


def test_zero_pose_puts_the_flange_where_franka_says():
    reference = load("reference")
    transforms, mse = reference.forward_kinematics(
        np.zeros((1, 7)),
        reference.column_major(np.eye(4))[None],
        reference.column_major(np.eye(4))[None],
    )
    last = reference.from_column_major(transforms[0, 96:])[0]
    flange = last @ np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.107], [0, 0, 0, 1]])
    # With every joint at 0 the flange is 0.088 m forward, 0.926 m up, pointing down.
    np.testing.assert_allclose(flange[:3, 3], [0.088, 0.0, 0.926], atol=1e-12)
    np.testing.assert_allclose(flange[:3, :3], np.diag([1.0, -1.0, -1.0]), atol=1e-12)
    assert mse[0] > 0.5  # O_T_EE = identity is far from that pose


def test_transforms_are_rigid_and_chain_through_each_joint():
    reference = load("reference")
    q, _, _ = states(200, seed=1)
    frames = reference.joint_transforms(q)
    rotation = frames[..., :3, :3]
    identity = np.broadcast_to(np.eye(3), rotation.shape)
    np.testing.assert_allclose(rotation @ np.swapaxes(rotation, -1, -2), identity, atol=1e-12)
    np.testing.assert_allclose(np.linalg.det(rotation), 1.0, atol=1e-12)
    # Joint i turns frame i about its own z axis: frame i's z axis does not depend on q_i.
    moved = q.copy()
    moved[:, 3] += 0.5
    np.testing.assert_allclose(
        reference.joint_transforms(moved)[:, 3, :3, 2], frames[:, 3, :3, 2], atol=1e-12
    )


def test_mse_is_zero_when_the_measured_pose_is_the_computed_one():
    reference = load("reference")
    q, f_t_ee, _ = states(50, seed=2)
    frames = reference.joint_transforms(q)
    flange = np.eye(4)
    flange[2, 3] = 0.107
    end = frames[:, 6] @ flange @ reference.from_column_major(f_t_ee)
    _, mse = reference.forward_kinematics(q, f_t_ee, reference.column_major(end))
    assert np.abs(mse).max() <= 1e-30
