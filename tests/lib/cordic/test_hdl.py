"""The CORDIC blocks against the model: MyHDL simulation and GHDL co-simulation, both kinds."""

from __future__ import annotations

import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal, intbv

from rfc.lib.cordic import CordicConfig, vectoring
from rfc.lib.cordic.hdl import cordic_vectoring
from rfc.toolchain import convert_myhdl, elaboration
from tests.support.cosim import run_handshake, signed, unsigned
from tests.support.myhdl_stream import simulate_stream


def signed_signal(bits: int) -> Signal:
    return Signal(intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1)))


def cordic_ports(config: CordicConfig) -> dict[str, Signal]:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "x": signed_signal(config.width),
        "y": signed_signal(config.width),
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "angle": signed_signal(config.angle_width),
        "magnitude": Signal(intbv(0)[config.magnitude_width :]),
    }


PORT_ORDER = ("clk", "rst", "in_valid", "in_ready", "x", "y", "out_valid", "out_ready", "angle",
              "magnitude")  # fmt: skip


def arguments(ports: dict[str, Signal], config: CordicConfig, pipelined: bool) -> list:
    return [*(ports[name] for name in PORT_ORDER), config, pipelined]


def edge_pairs(config: CordicConfig) -> list[tuple[int, int]]:
    low, high = -(1 << (config.width - 1)), (1 << (config.width - 1)) - 1
    return [(0, 0), (low, low), (low, 0), (0, low), (high, high), (low, high), (high, low),
            (-1, 0), (1, 0), (0, 1), (0, -1), (-1, -1), (high, 0), (0, high)]  # fmt: skip


def latency(config: CordicConfig, pipelined: bool) -> int:
    """Cycles from the input handshake to `out_valid`: a cycle per stage, or two per iteration."""
    return config.iterations if pipelined else 2 * config.iterations


def expected(pairs, config):
    results = [vectoring(x, y, config) for x, y in pairs]
    return [r.angle for r in results], [r.magnitude for r in results]


@settings(max_examples=12)
@given(
    width=st.integers(4, 40),
    iterations=st.integers(2, 24),
    angle_frac=st.integers(8, 40),
    pipelined=st.booleans(),
    data=st.data(),
)
def test_myhdl_simulation_matches_the_model(width, iterations, angle_frac, pipelined, data):
    config = CordicConfig(width, iterations, angle_frac)
    value = st.integers(-(1 << (width - 1)), (1 << (width - 1)) - 1)
    pairs = edge_pairs(config) + data.draw(st.lists(st.tuples(value, value), max_size=12))
    ports = cordic_ports(config)
    run = simulate_stream(
        cordic_vectoring,
        arguments(ports, config, pipelined),
        ports,
        {"x": [p[0] for p in pairs], "y": [p[1] for p in pairs]},
        ["angle", "magnitude"],
        seed=data.draw(st.integers(0, 1000)),
    )
    angles, magnitudes = expected(pairs, config)
    assert run.outputs == {"angle": angles, "magnitude": magnitudes}
    assert min(run.latencies) == latency(config, pipelined)
    documented = config.pipelined_latency if pipelined else config.iterative_latency
    assert documented == latency(config, pipelined)


@pytest.mark.parametrize(
    ("config", "pipelined"),
    [(CordicConfig(64, 44, 60), False), (CordicConfig(20, 16, 18), True)],
    ids=["iterative-64x44", "pipelined-20x16"],
)
def test_converted_vhdl_matches_the_model_under_backpressure(tmp_path, config, pipelined):
    rng = random.Random(7)
    low, high = -(1 << (config.width - 1)), (1 << (config.width - 1)) - 1
    pairs = edge_pairs(config) + [
        (rng.randint(low, high), rng.randint(low, high)) for _ in range(150)
    ]
    with elaboration():
        dut = cordic_vectoring(*arguments(cordic_ports(config), config, pipelined))
        files = convert_myhdl(dut, "cordic", tmp_path)
    angles, magnitudes = expected(pairs, config)
    width = config.width
    run = run_handshake(
        files,
        "cordic",
        {"x": [unsigned(x, width) for x, _ in pairs], "y": [unsigned(y, width) for _, y in pairs]},
        ["angle", "magnitude"],
        tmp_path,
        expected={
            "angle": [unsigned(a, config.angle_width) for a in angles],
            "magnitude": magnitudes,
        },
    )
    assert [signed(a, config.angle_width) for a in run.outputs["angle"]] == angles
    assert min(run.latencies) == latency(config, pipelined)
    if not pipelined:
        assert set(run.latencies) == {latency(config, pipelined)}


# Iterative: two cycles per micro-rotation, then the result is offered for a cycle and the block
# is idle for one.
@pytest.mark.parametrize(("pipelined", "interval"), [(False, 2 * 12 + 2), (True, 1)])
def test_initiation_interval(pipelined, interval):
    config = CordicConfig(16, 12, 14)
    ports = cordic_ports(config)
    run = simulate_stream(
        cordic_vectoring,
        arguments(ports, config, pipelined),
        ports,
        {"x": [5, -6, 7, 0], "y": [1, 2, -3, 0]},
        ["angle"],
        idle=0.0,
        backpressure=0.0,
    )
    assert set(np.diff(run.accepted)) == {interval}
    assert set(run.latencies) == {latency(config, pipelined)}
    if not pipelined:
        assert config.iterative_interval == interval
