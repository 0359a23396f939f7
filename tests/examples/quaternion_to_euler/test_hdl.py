"""Both accelerator cores in GHDL (cocotb) and in MyHDL against their references.

Bits must equal the core's bit-accurate reference exactly; the angles must then be within the
issue's tolerance of NumPy; a quaternion takes the core's latency (the iterative core exactly
that, the pipelined one that at least, longer while the consumer stalls it), under random idle
cycles and backpressure, including inputs outside the domain (which give NaNs and recover).
GHDL takes every fourth orientation of each set; every one goes through the iterative core in
Verilator here and through the pipelined one in the whole system (test_system.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.toolchain import convert_myhdl, elaboration
from tests.conftest import shared_file
from tests.examples.quaternion_to_euler.example import (
    Core,
    core_arguments,
    core_ports,
    cores,
    example,
)
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


CORES = {core.name: core for core in cores()}
BOTH = pytest.mark.parametrize("core", list(CORES.values()), ids=list(CORES))
#: GHDL runs either core at about ten quaternions a second (the iterative one takes 195 cycles
#: a quaternion, the pipelined one evaluates all its stages on every cycle): it gets every fourth
#: orientation of each set.
GHDL_STRIDE = 4


def expected_bits(core: Core, quaternions: np.ndarray) -> dict[str, list[int]]:
    rows = [core.reference(q) for q in quaternions]
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


def cosimulate(tmp_path, core: Core, quaternions: np.ndarray, seed: int, simulator: str = "ghdl"):
    with elaboration():
        instance = core.block(*core_arguments(core_ports()))
        verilog = simulator == "verilator"
        files = convert_myhdl(instance, "quat_to_euler", tmp_path, verilog=verilog)
    expected = expected_bits(core, quaternions)
    run = run_handshake(
        files,
        "quat_to_euler",
        as_bits(quaternions),
        list(expected),
        tmp_path,
        expected=expected,
        seed=seed,
        compiled=True,
        simulator=simulator,
    )
    assert run.outputs == expected
    assert_latency(core, run.latencies)
    return angles(run.outputs)


def assert_latency(core: Core, latencies: list[int]) -> None:
    if core.interval == 1:
        assert min(latencies) == core.latency
    else:
        assert set(latencies) == {core.latency}


def domain_rows(quaternions: np.ndarray) -> np.ndarray:
    return np.isfinite(quaternions).all(axis=1) & (np.abs(quaternions) < 2).all(axis=1)


@BOTH
@pytest.mark.parametrize("half", [0, 1], ids=["first-half", "second-half"])
def test_ghdl_equals_the_reference_on_a_thousand_orientations(tmp_path, core, half):
    chosen = np.array_split(orientation_set(), 2)[half][::GHDL_STRIDE]
    quaternions = with_out_of_domain(chosen)
    hardware = cosimulate(tmp_path, core, quaternions, seed=half)
    inside = domain_rows(quaternions)
    assert np.isnan(hardware[~inside]).all()
    check_against_numpy(hardware[inside], quaternions[inside], example().numpy_reference)


@BOTH
@pytest.mark.parametrize("half", [0, 1], ids=["first-half", "second-half"])
def test_ghdl_equals_the_reference_on_every_odom_orientation(tmp_path, core, half):
    quaternions = np.array_split(
        distinct(odom_orientations(shared_file("bags/nav2_turtlebot.mcap"))), 2
    )[half][::GHDL_STRIDE]
    hardware = cosimulate(tmp_path, core, quaternions, seed=10 + half)
    check_against_numpy(hardware, quaternions, example().numpy_reference)


def test_verilator_equals_the_reference_on_every_orientation_through_the_iterative_core(
    tmp_path, monkeypatch
):
    # 3,479 orientations: a model at Verilator's own g++ flags, not the suite's -O0 (22 s, 42 s)
    monkeypatch.delenv("RFC_VERILATOR_OPT", raising=False)
    core = CORES["iterative"]
    odom = distinct(odom_orientations(shared_file("bags/nav2_turtlebot.mcap")))
    quaternions = with_out_of_domain(np.concatenate([orientation_set(), odom]))
    hardware = cosimulate(tmp_path, core, quaternions, seed=20, simulator="verilator")
    inside = domain_rows(quaternions)
    assert np.isnan(hardware[~inside]).all()
    check_against_numpy(hardware[inside], quaternions[inside], example().numpy_reference)


def simulate_in_myhdl(core: Core, quaternions: np.ndarray, **stream):
    ports = core_ports()
    arguments = core_arguments(ports)
    outputs = ["roll", "pitch", "yaw"]
    return simulate_stream(core.block, arguments, ports, as_bits(quaternions), outputs, **stream)


@BOTH
def test_myhdl_simulation_equals_the_reference(core):
    quaternions = with_out_of_domain(orientation_set()[::40])
    run = simulate_in_myhdl(core, quaternions)
    assert run.outputs == expected_bits(core, quaternions)
    assert_latency(core, run.latencies)


@BOTH
def test_myhdl_takes_a_quaternion_every_initiation_interval(core):
    run = simulate_in_myhdl(core, orientation_set()[:6], idle=0.0, backpressure=0.0)
    assert set(np.diff(run.accepted)) == {core.interval}
    assert set(run.latencies) == {core.latency}


def test_the_pipelined_core_holds_its_results_while_the_consumer_stalls():
    # Every result waits for the consumer; none is lost or repeated, and once the pipeline is
    # full it takes a new quaternion only as a result leaves (the consumer refuses half the
    # cycles).
    core = CORES["pipelined"]
    quaternions = orientation_set()[: core.latency + 15]
    run = simulate_in_myhdl(core, quaternions, idle=0.0, backpressure=0.5)
    assert run.outputs == expected_bits(core, quaternions)
    assert max(np.diff(run.accepted)) > 1
