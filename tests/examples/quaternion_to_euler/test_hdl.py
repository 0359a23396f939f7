"""The accelerator core in GHDL (cocotb) and in MyHDL against its references.

Bits must equal the bit-accurate reference exactly; the angles must then be within the issue's
tolerance of NumPy; every quaternion must take exactly LATENCY cycles, under random idle
cycles and backpressure, including inputs outside the domain (which give NaNs and recover).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.toolchain import convert_myhdl
from tests.conftest import shared_file
from tests.examples.quaternion_to_euler.example import core_arguments, core_ports, example
from tests.examples.quaternion_to_euler.quaternions import (
    check_against_numpy,
    distinct,
    odom_orientations,
    orientation_set,
)
from tests.support.cosim import run_handshake
from tests.support.myhdl_stream import simulate_stream

#: Items outside the domain, spread through a stream to show the core flags them and recovers.
OUT_OF_DOMAIN = np.array(
    [[math.nan, 0.0, 0.0, 1.0], [0.0, math.inf, 0.0, 1.0], [0.0, 0.0, -3.0, 0.5]]
)


def as_bits(quaternions: np.ndarray) -> dict[str, list[int]]:
    return {
        axis: [float_to_bits(float(v)) for v in quaternions[:, i]] for i, axis in enumerate("xyzw")
    }


def expected_bits(quaternions: np.ndarray) -> dict[str, list[int]]:
    rows = [example().reference(*(float_to_bits(float(c)) for c in q)) for q in quaternions]
    return {name: [row[i] for row in rows] for i, name in enumerate(("roll", "pitch", "yaw"))}


def angles(outputs: dict[str, list[int]]) -> np.ndarray:
    return np.array(
        [[bits_to_float(b) for b in outputs[name]] for name in ("roll", "pitch", "yaw")]
    ).T


def with_out_of_domain(quaternions: np.ndarray) -> np.ndarray:
    rows = list(quaternions)
    for i, bad in enumerate(OUT_OF_DOMAIN):
        rows.insert(1 + i * len(rows) // len(OUT_OF_DOMAIN), bad)
    return np.array(rows)


def cosimulate(tmp_path, quaternions: np.ndarray, seed: int):
    files = convert_myhdl(
        example().quat_to_euler(*core_arguments(core_ports())), "quat_to_euler", tmp_path
    )
    expected = expected_bits(quaternions)
    run = run_handshake(
        files,
        "quat_to_euler",
        as_bits(quaternions),
        list(expected),
        tmp_path,
        expected=expected,
        seed=seed,
    )
    assert run.outputs == expected
    assert set(run.latencies) == {example().LATENCY}
    return angles(run.outputs)


def domain_rows(quaternions: np.ndarray) -> np.ndarray:
    return np.isfinite(quaternions).all(axis=1) & (np.abs(quaternions) < 2).all(axis=1)


@pytest.mark.parametrize("half", [0, 1], ids=["first-half", "second-half"])
def test_ghdl_equals_the_reference_on_a_thousand_orientations(tmp_path, half):
    quaternions = with_out_of_domain(np.array_split(orientation_set(), 2)[half])
    hardware = cosimulate(tmp_path, quaternions, seed=half)
    inside = domain_rows(quaternions)
    assert np.isnan(hardware[~inside]).all()
    check_against_numpy(hardware[inside], quaternions[inside], example().numpy_reference)


@pytest.mark.parametrize("half", [0, 1], ids=["first-half", "second-half"])
def test_ghdl_equals_the_reference_on_every_odom_orientation(tmp_path, half):
    quaternions = np.array_split(
        distinct(odom_orientations(shared_file("bags/nav2_turtlebot.mcap"))), 2
    )[half]
    hardware = cosimulate(tmp_path, quaternions, seed=10 + half)
    check_against_numpy(hardware, quaternions, example().numpy_reference)


def simulate_in_myhdl(quaternions: np.ndarray, **stream):
    ports = core_ports()
    arguments = core_arguments(ports)
    outputs = ["roll", "pitch", "yaw"]
    return simulate_stream(
        example().quat_to_euler, arguments, ports, as_bits(quaternions), outputs, **stream
    )


def test_myhdl_simulation_equals_the_reference():
    quaternions = with_out_of_domain(orientation_set()[::40])
    run = simulate_in_myhdl(quaternions)
    assert run.outputs == expected_bits(quaternions)
    assert set(run.latencies) == {example().LATENCY}


def test_myhdl_takes_a_quaternion_every_initiation_interval():
    run = simulate_in_myhdl(orientation_set()[:4], idle=0.0, backpressure=0.0)
    assert set(np.diff(run.accepted)) == {example().INITIATION_INTERVAL}
