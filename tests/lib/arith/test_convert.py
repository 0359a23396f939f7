"""The pipelined float64 ↔ fixed converters against rfc.lib.fixed's models: MyHDL and GHDL."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal, intbv

from rfc.lib.arith.convert_hdl import (
    FIXED_TO_FLOAT_LATENCY,
    FLOAT_TO_FIXED_LATENCY,
    fixed_to_float_pipelined,
    float_to_fixed_pipelined,
)
from rfc.lib.fixed import FixedFormat, fixed_to_float, float_to_bits, float_to_fixed
from rfc.toolchain import convert_myhdl, elaboration, module_estimate
from tests.lib.fixed.strategies import floats_near, formats, sample_floats
from tests.support.cosim import run_handshake, signed, unsigned
from tests.support.myhdl_stream import simulate_stream

TO_FIXED = ("clk", "rst", "in_valid", "in_ready", "bits", "out_valid", "out_ready", "raw",
            "overflow", "invalid")  # fmt: skip
TO_FLOAT = ("clk", "rst", "in_valid", "in_ready", "raw", "out_valid", "out_ready", "bits")


def ports(fmt: FixedFormat) -> dict[str, Signal]:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "bits": Signal(intbv(0)[64:]),
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "raw": fmt.signal(),
        "overflow": Signal(bool(0)),
        "invalid": Signal(bool(0)),
    }


def to_fixed_rows(values: list[float], fmt: FixedFormat) -> dict[str, list[int]]:
    results = [float_to_fixed(float_to_bits(v), fmt) for v in values]
    return {
        "raw": [r.raw for r in results],
        "overflow": [int(r.overflow) for r in results],
        "invalid": [int(r.invalid) for r in results],
    }


@settings(max_examples=12)
@given(st.data())
def test_myhdl_float_to_fixed_matches_the_model(data):
    fmt = data.draw(formats(max_width=80))
    values = data.draw(st.lists(floats_near(fmt), min_size=1, max_size=20))
    signals = ports(fmt)
    run = simulate_stream(
        float_to_fixed_pipelined,
        [*(signals[n] for n in TO_FIXED), fmt],
        signals,
        {"bits": [float_to_bits(v) for v in values]},
        ["raw", "overflow", "invalid"],
        seed=data.draw(st.integers(0, 1000)),
    )
    assert run.outputs == to_fixed_rows(values, fmt)
    assert min(run.latencies) == FLOAT_TO_FIXED_LATENCY


@settings(max_examples=12)
@given(st.data())
def test_myhdl_fixed_to_float_matches_the_model(data):
    fmt = data.draw(formats(max_width=80))
    raws = data.draw(st.lists(st.integers(fmt.min_raw, fmt.max_raw), min_size=1, max_size=20))
    signals = ports(fmt)
    run = simulate_stream(
        fixed_to_float_pipelined,
        [*(signals[n] for n in TO_FLOAT), fmt],
        signals,
        {"raw": raws},
        ["bits"],
        seed=data.draw(st.integers(0, 1000)),
    )
    assert run.outputs["bits"] == [fixed_to_float(r, fmt) for r in raws]
    assert min(run.latencies) == FIXED_TO_FLOAT_LATENCY


def test_converted_vhdl_matches_the_models_under_backpressure(tmp_path):
    fmt = FixedFormat(50, 44)
    values = sample_floats(fmt, 120)
    signals = ports(fmt)
    with elaboration():
        to_fixed = convert_myhdl(
            float_to_fixed_pipelined(*(signals[n] for n in TO_FIXED), fmt),
            "to_fixed",
            tmp_path / "a",
        )
    want = to_fixed_rows(values, fmt)
    run = run_handshake(
        to_fixed,
        "to_fixed",
        {"bits": [float_to_bits(v) for v in values]},
        ["raw", "overflow", "invalid"],
        tmp_path / "a",
    )
    assert [signed(r, fmt.width) for r in run.outputs["raw"]] == want["raw"]
    assert run.outputs["overflow"] == want["overflow"]
    assert run.outputs["invalid"] == want["invalid"]
    with elaboration():
        to_float = convert_myhdl(
            fixed_to_float_pipelined(*(signals[n] for n in TO_FLOAT), fmt),
            "to_float",
            tmp_path / "b",
        )
    raws = want["raw"]
    run = run_handshake(
        to_float,
        "to_float",
        {"raw": [unsigned(r, fmt.width) for r in raws]},
        ["bits"],
        tmp_path / "b",
    )
    assert run.outputs["bits"] == [fixed_to_float(r, fmt) for r in raws]


@pytest.mark.parametrize("to_fixed", [True, False])
def test_a_value_every_cycle(to_fixed):
    fmt = FixedFormat(16, 8)
    signals = ports(fmt)
    block, order = (
        (float_to_fixed_pipelined, TO_FIXED) if to_fixed else (fixed_to_float_pipelined, TO_FLOAT)
    )
    name = "bits" if to_fixed else "raw"
    run = simulate_stream(
        block,
        [*(signals[n] for n in order), fmt],
        signals,
        {name: [1, 2, 3, 4, 5]},
        [order[7]],
        idle=0.0,
        backpressure=0.0,
    )
    assert set(np.diff(run.accepted)) == {1}


@pytest.mark.parametrize("to_fixed", [True, False], ids=["float_to_fixed", "fixed_to_float"])
def test_the_converters_stay_within_half_a_100_mhz_period_of_cell_delay(tmp_path, to_fixed):
    fmt = FixedFormat(46, 44)  # the pipelined quaternion core's components
    signals = ports(fmt)
    block, order = (
        (float_to_fixed_pipelined, TO_FIXED) if to_fixed else (fixed_to_float_pipelined, TO_FLOAT)
    )
    with elaboration():
        files = convert_myhdl(block(*(signals[n] for n in order), fmt), "convert", tmp_path)
    timing = module_estimate(files[-1], "convert").timing  # what `--estimate` reports of it
    # The combinational float → fixed conversion between two registers took 8.4 ns.
    assert timing is not None
    assert 0 < timing.delay_ps <= 3500
