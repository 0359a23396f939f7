"""The HLS C++ version, compiled with g++ and run through its test driver, against NumPy."""

from __future__ import annotations

import math
import shutil
import subprocess

import numpy as np
import pytest

from rfc.lib.fixed import bits_to_float, float_to_bits
from tests.conftest import shared_file
from tests.examples.quaternion_to_euler.example import HLS, example
from tests.examples.quaternion_to_euler.quaternions import (
    check_against_numpy,
    odom_orientations,
    orientation_set,
)

SOURCES = ["QuaternionToEulerConverter.cpp", "QuaternionToEulerConverter_tb.cpp"]


@pytest.fixture(scope="module")
def driver(tmp_path_factory):
    compiler = shutil.which("g++")
    assert compiler, "g++ is needed to test the HLS version (Debian package g++)"
    binary = tmp_path_factory.mktemp("hls") / "quaternion_to_euler"
    flags = ["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", "-Wno-unknown-pragmas"]
    subprocess.run(
        [compiler, *flags, f"-I{HLS}", *(str(HLS / s) for s in SOURCES), "-o", str(binary)],
        check=True,
        capture_output=True,
    )
    return binary


def run(driver, quaternions: np.ndarray) -> np.ndarray:
    lines = "".join(
        " ".join(f"{float_to_bits(float(c)):016x}" for c in q) + "\n" for q in quaternions
    )
    result = subprocess.run([driver], input=lines, capture_output=True, text=True, check=True)
    rows = [line.split() for line in result.stdout.splitlines()]
    return np.array([[bits_to_float(int(v, 16)) for v in row] for row in rows])


def test_hls_version_is_within_tolerance_of_numpy_on_a_thousand_orientations(driver):
    quaternions = orientation_set()
    check_against_numpy(run(driver, quaternions), quaternions, example().numpy_reference)


def test_hls_version_is_within_tolerance_of_numpy_on_a_recorded_bag(driver):
    quaternions = odom_orientations(shared_file("bags/nav2_turtlebot.mcap"))
    check_against_numpy(run(driver, quaternions), quaternions, example().numpy_reference)


def test_hls_version_gives_nans_outside_the_domain_like_the_core(driver):
    outside = np.array([[math.nan, 0, 0, 1], [0, math.inf, 0, 1], [0, 0, 2.0, 0], [-3.0, 0, 0, 0]])
    assert np.isnan(run(driver, outside)).all()
