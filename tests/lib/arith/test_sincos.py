"""Sine/cosine: the model against NumPy, both MyHDL blocks and their VHDL against the model."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal

from rfc.lib.arith import SinCosConfig, sincos
from rfc.lib.arith.sincos_hdl import sincos as sincos_block
from rfc.toolchain import convert_myhdl, elaboration
from tests.support.cosim import run_handshake, signed, unsigned
from tests.support.myhdl_stream import simulate_stream

PORT_ORDER = ("clk", "rst", "in_valid", "in_ready", "angle", "out_valid", "out_ready", "cos", "sin")
ACCURATE = SinCosConfig(44)


def ports(config: SinCosConfig) -> dict[str, Signal]:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "angle": config.angle_format.signal(),
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "cos": config.out_format.signal(),
        "sin": config.out_format.signal(),
    }


def arguments(signals: dict[str, Signal], config: SinCosConfig, pipelined: bool) -> list:
    return [*(signals[name] for name in PORT_ORDER), config, pipelined]


def edge_angles(config: SinCosConfig) -> list[int]:
    """The format's ends, 0, and raw angles next to multiples of π/2 (the reduction's edges)."""
    fmt = config.angle_format
    scale = 2.0**fmt.frac_bits
    near = [round(k * np.pi / 2 * scale) + d for k in range(-5, 6) for d in (-1, 0, 1)]
    return [fmt.min_raw, fmt.max_raw, 0, *(a for a in near if fmt.min_raw <= a <= fmt.max_raw)]


def test_fixed_angles_within_1e12_of_numpy_over_the_whole_format():
    fmt = ACCURATE.angle_format  # [-8, 8) rad, beyond [-2π, 2π]
    rng = np.random.default_rng(1)
    raw = rng.integers(fmt.min_raw, fmt.max_raw, 200_000, endpoint=True)
    raw = np.concatenate([raw, edge_angles(ACCURATE)])
    angle = raw / 2.0**44  # exact: raw has at most 48 bits
    cos, sin = sincos(raw, ACCURATE)
    assert np.abs(cos / 2.0**44 - np.cos(angle)).max() <= 1e-12
    assert np.abs(sin / 2.0**44 - np.sin(angle)).max() <= 1e-12


def test_float64_angles_within_1e12_of_numpy_after_rounding_to_the_format():
    rng = np.random.default_rng(2)
    angle = rng.uniform(-2 * np.pi, 2 * np.pi, 200_000)
    raw = np.rint(angle * 2.0**44).astype(np.int64)  # float64 → fixed, ties to even
    cos, sin = sincos(raw, ACCURATE)
    assert np.abs(cos / 2.0**44 - np.cos(angle)).max() <= 1e-12
    assert np.abs(sin / 2.0**44 - np.sin(angle)).max() <= 1e-12


def test_angles_outside_the_format_are_refused():
    with pytest.raises(ValueError, match="raw integers"):
        sincos(np.array([ACCURATE.angle_format.max_raw + 1]), ACCURATE)


def test_configurations_the_model_cannot_hold_are_refused():
    with pytest.raises(ValueError, match="wider than"):
        SinCosConfig(56)


@settings(max_examples=10)
@given(frac_bits=st.integers(6, 40), pipelined=st.booleans(), data=st.data())
def test_myhdl_simulation_matches_the_model(frac_bits, pipelined, data):
    config = SinCosConfig(frac_bits)
    fmt = config.angle_format
    drawn = data.draw(st.lists(st.integers(fmt.min_raw, fmt.max_raw), max_size=10))
    angles = edge_angles(config)[:12] + drawn
    signals = ports(config)
    run = simulate_stream(
        sincos_block,
        arguments(signals, config, pipelined),
        signals,
        {"angle": angles},
        ["cos", "sin"],
        seed=data.draw(st.integers(0, 1000)),
    )
    cos, sin = sincos(np.array(angles), config)
    assert run.outputs == {"cos": cos.tolist(), "sin": sin.tolist()}
    assert min(run.latencies) == latency(config, pipelined)


@pytest.mark.parametrize(
    ("config", "pipelined"),
    [(ACCURATE, False), (SinCosConfig(20), True)],
    ids=["iterative-44", "pipelined-20"],
)
def test_converted_vhdl_matches_the_model_under_backpressure(tmp_path, config, pipelined):
    fmt, out = config.angle_format, config.out_format
    rng = np.random.default_rng(3)
    angles = edge_angles(config) + rng.integers(fmt.min_raw, fmt.max_raw, 60).tolist()
    with elaboration():
        files = convert_myhdl(
            sincos_block(*arguments(ports(config), config, pipelined)), "sincos", tmp_path / "hdl"
        )
    cos, sin = sincos(np.array(angles), config)
    run = run_handshake(
        files,
        "sincos",
        {"angle": [unsigned(a, fmt.width) for a in angles]},
        ["cos", "sin"],
        tmp_path,
    )
    assert [signed(c, out.width) for c in run.outputs["cos"]] == cos.tolist()
    assert [signed(s, out.width) for s in run.outputs["sin"]] == sin.tolist()
    assert min(run.latencies) == latency(config, pipelined)


@pytest.mark.parametrize(("pipelined", "interval"), [(False, 15), (True, 1)])
def test_initiation_interval(pipelined, interval):
    config = SinCosConfig(10)
    signals = ports(config)
    run = simulate_stream(
        sincos_block,
        arguments(signals, config, pipelined),
        signals,
        {"angle": [5, -600, 7000, 0]},
        ["cos"],
        idle=0.0,
        backpressure=0.0,
    )
    assert set(np.diff(run.accepted)) == {interval}
    assert set(run.latencies) == {latency(config, pipelined)}


def latency(config: SinCosConfig, pipelined: bool) -> int:
    return config.latency if pipelined else config.iterative_latency
