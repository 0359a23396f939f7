"""The bit-accurate reference against NumPy, and the behaviours users rely on."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rfc.lib.fixed import QUIET_NAN, bits_to_float, float_to_bits
from tests.conftest import shared_file
from tests.examples.quaternion_to_euler.example import example
from tests.examples.quaternion_to_euler.quaternions import (
    check_against_numpy,
    odom_orientations,
    orientation_set,
)


def reference_angles(quaternions: np.ndarray) -> np.ndarray:
    reference = example().reference
    rows = [reference(*(float_to_bits(float(c)) for c in q)) for q in quaternions]
    return np.array([[bits_to_float(b) for b in row] for row in rows])


def test_reference_is_within_tolerance_of_numpy_on_a_thousand_orientations():
    quaternions = orientation_set()
    check_against_numpy(reference_angles(quaternions), quaternions, example().numpy_reference)


def test_reference_is_within_tolerance_of_numpy_on_a_recorded_bag():
    quaternions = odom_orientations(shared_file("bags/nav2_turtlebot.mcap"))
    assert len(quaternions) == 2639
    check_against_numpy(reference_angles(quaternions), quaternions, example().numpy_reference)


def test_level_orientations_give_exact_zeros():
    # A robot at rest or driving on the flat: roll and pitch exactly 0, yaw exactly 0 at rest.
    assert reference_angles(np.array([[0.0, 0.0, 0.0, 1.0]])).tolist() == [[0.0, 0.0, 0.0]]
    planar = reference_angles(np.array([[-0.0, 0.0, 0.0845736, -0.99641724]]))
    assert planar[0, :2].tolist() == [0.0, 0.0]


def test_a_quaternion_and_its_negation_give_the_same_bits():
    quaternions = orientation_set()[:200]
    assert (reference_angles(quaternions) == reference_angles(-quaternions)).all()


@pytest.mark.parametrize(
    "quaternion",
    [
        [math.nan, 0.0, 0.0, 1.0],
        [0.0, math.inf, 0.0, 1.0],
        [0.0, 0.0, -math.inf, 1.0],
        [0.0, 0.0, 0.0, 2.0],
        [0.0, -3.0, 0.0, 0.0],
    ],
)
def test_components_outside_the_domain_give_quiet_nans(quaternion):
    bits = example().reference(*(float_to_bits(c) for c in quaternion))
    assert bits == (QUIET_NAN, QUIET_NAN, QUIET_NAN)


def test_latency_meets_the_target():
    assert example().LATENCY <= 120
