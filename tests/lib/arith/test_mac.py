"""Multiply and multiply-accumulate: models against exact rationals and NumPy, blocks against
the models in MyHDL and GHDL."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal, block

from rfc.lib.arith.mac import multiply, multiply_accumulate
from rfc.lib.arith.mac_hdl import (
    MULTIPLY_LATENCY,
    exact_multiply,
    exact_multiply_stages,
    fixed_mac,
    fixed_multiply,
    mac_latency,
)
from rfc.lib.arith.pipeline import handshakes, stage_register
from rfc.lib.fixed import FixedFormat
from rfc.toolchain import convert_myhdl, elaboration
from tests.lib.arith.synth import map_xc7
from tests.support.cosim import run_handshake, signed, unsigned
from tests.support.myhdl_stream import simulate_stream

WIDE = FixedFormat(50, 44)
MULTIPLY_ORDER = ("clk", "rst", "in_valid", "in_ready", "a", "b", "out_valid", "out_ready",
                  "product")  # fmt: skip
MAC_ORDER = ("clk", "rst", "in_valid", "in_ready", "a", "b", "first", "out_valid", "out_ready",
             "total")  # fmt: skip


def ports(fmt: FixedFormat) -> dict[str, Signal]:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "a": fmt.signal(),
        "b": fmt.signal(),
        "first": Signal(bool(0)),
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "product": fmt.signal(),
        "total": fmt.signal(),
    }


def assert_rounded(got: np.ndarray, total: np.ndarray, fmt: FixedFormat) -> None:
    """Each result is `total` (2·frac_bits fraction bits) rounded half up, or the format's end.

    Round half up to r means r - 1/2 <= value < r + 1/2, in integers
    (2r - 1)·2**(f - 1) <= total < (2r + 1)·2**(f - 1); saturation gives the nearer end.
    """
    half = 1 << (fmt.frac_bits - 1)
    inside = (got > fmt.min_raw) & (got < fmt.max_raw)
    assert np.all(((2 * got - 1) * half <= total)[inside])
    assert np.all((total < (2 * got + 1) * half)[inside])
    assert np.all((total >= (2 * got - 1) * half)[got == fmt.max_raw])
    assert np.all((total < (2 * got + 1) * half)[got == fmt.min_raw])
    assert inside.mean() > 0.9  # most results are not saturated


def raw_values(rng: np.random.Generator, fmt: FixedFormat, count: int) -> np.ndarray:
    """Raw integers of `fmt` spread over magnitudes (as Python ints: products need > 64 bits)."""
    top = np.int64(1) << rng.integers(0, fmt.width - 1, count)
    values = np.clip(rng.integers(-top, top), fmt.min_raw, fmt.max_raw)
    return np.concatenate([[fmt.min_raw, fmt.max_raw], values[2:]]).astype(object)


def test_multiply_model_rounds_the_exact_product_over_100k_pairs():
    rng = np.random.default_rng(1)
    a, b = raw_values(rng, WIDE, 100_000), raw_values(rng, WIDE, 100_000)
    got = multiply(a, b, WIDE)
    assert_rounded(got, a * b, WIDE)
    # And within half a unit of NumPy's float product where nothing saturates.
    product = a.astype(float) * b.astype(float) / 2.0 ** (2 * WIDE.frac_bits)
    inside = np.abs(product) < 2.0 ** (WIDE.int_bits - 2)
    error = np.abs(got.astype(float) / 2.0**WIDE.frac_bits - product)[inside]
    assert error.max() <= 2.0 ** -(WIDE.frac_bits + 1) * (1 + 1e-9) + 1e-15


def test_mac_model_rounds_the_exact_sum_over_100k_sums():
    rng = np.random.default_rng(2)
    terms = [(raw_values(rng, WIDE, 100_000), raw_values(rng, WIDE, 100_000)) for _ in range(16)]
    got = multiply_accumulate(terms, WIDE)
    assert_rounded(got, sum(a * b for a, b in terms), WIDE)


def test_sums_beyond_the_guard_bits_are_refused():
    with pytest.raises(ValueError, match="1 to 16 products"):
        multiply_accumulate([(1, 1)] * 17, WIDE)


@settings(max_examples=10)
@given(width=st.integers(4, 60), data=st.data())
def test_myhdl_multiply_matches_the_model(width, data):
    fmt = FixedFormat(width, data.draw(st.integers(1, width)))
    value = st.integers(fmt.min_raw, fmt.max_raw)
    pairs = data.draw(st.lists(st.tuples(value, value), min_size=1, max_size=20))
    signals = ports(fmt)
    run = simulate_stream(
        fixed_multiply,
        [*(signals[n] for n in MULTIPLY_ORDER), fmt],
        signals,
        {"a": [a for a, _ in pairs], "b": [b for _, b in pairs]},
        ["product"],
        seed=data.draw(st.integers(0, 1000)),
    )
    assert run.outputs["product"] == [multiply(a, b, fmt) for a, b in pairs]
    assert min(run.latencies) == MULTIPLY_LATENCY


def running_sums(pairs, firsts, fmt):
    out, terms = [], []
    for pair, first in zip(pairs, firsts, strict=True):
        terms = [pair] if first else [*terms, pair]
        out.append(multiply_accumulate(terms, fmt))
    return out


@settings(max_examples=10)
@given(width=st.integers(4, 60), data=st.data())
def test_myhdl_mac_matches_the_model(width, data):
    fmt = FixedFormat(width, data.draw(st.integers(1, width)))
    value = st.integers(fmt.min_raw, fmt.max_raw)
    pairs = data.draw(st.lists(st.tuples(value, value), min_size=1, max_size=30))
    firsts = [i % 16 == 0 or data.draw(st.booleans()) for i in range(len(pairs))]
    signals = ports(fmt)
    run = simulate_stream(
        fixed_mac,
        [*(signals[n] for n in MAC_ORDER), fmt],
        signals,
        {"a": [a for a, _ in pairs], "b": [b for _, b in pairs], "first": firsts},
        ["total"],
        seed=data.draw(st.integers(0, 1000)),
    )
    assert run.outputs["total"] == running_sums(pairs, firsts, fmt)
    assert min(run.latencies) == mac_latency(fmt)


@pytest.mark.parametrize("mac", [False, True], ids=["multiply", "mac"])
def test_converted_vhdl_matches_the_model_under_backpressure(tmp_path, mac):
    rng = np.random.default_rng(4)
    a, b = raw_values(rng, WIDE, 80).tolist(), raw_values(rng, WIDE, 80).tolist()
    a[:4] = b[:4] = [WIDE.min_raw, WIDE.max_raw, WIDE.min_raw, -1]  # saturation both ways
    firsts = [i % 5 == 0 for i in range(80)]
    signals = ports(WIDE)
    with elaboration():
        if mac:
            dut = fixed_mac(*(signals[n] for n in MAC_ORDER), WIDE)
            want, output = running_sums(list(zip(a, b, strict=True)), firsts, WIDE), "total"
        else:
            dut = fixed_multiply(*(signals[n] for n in MULTIPLY_ORDER), WIDE)
            want, output = [multiply(x, y, WIDE) for x, y in zip(a, b, strict=True)], "product"
        files = convert_myhdl(dut, output, tmp_path / "hdl")
    inputs = {"a": [unsigned(x, 50) for x in a], "b": [unsigned(y, 50) for y in b]}
    if mac:
        inputs["first"] = [int(f) for f in firsts]
    run = run_handshake(files, output, inputs, [output], tmp_path)
    assert [signed(v, 50) for v in run.outputs[output]] == want
    assert min(run.latencies) == (mac_latency(WIDE) if mac else MULTIPLY_LATENCY)


@pytest.mark.parametrize("block", [fixed_multiply, fixed_mac])
def test_a_pair_every_cycle(block):
    fmt = FixedFormat(12, 6)
    signals = ports(fmt)
    order = MAC_ORDER if block is fixed_mac else MULTIPLY_ORDER
    inputs = {"a": [1, 2, 3, 4, 5], "b": [5, 4, 3, 2, 1]}
    if block is fixed_mac:
        inputs["first"] = [1, 0, 0, 1, 0]
    run = simulate_stream(
        block,
        [*(signals[n] for n in order), fmt],
        signals,
        inputs,
        [order[-1]],
        idle=0.0,
        backpressure=0.0,
    )
    assert set(np.diff(run.accepted)) == {1}


def test_a_one_slice_multiply_uses_all_four_dsp48_registers(tmp_path):
    fmt = FixedFormat(18, 16)  # 18 x 18 signed fits one DSP48E1 (25 x 18)
    signals = ports(fmt)
    with elaboration():
        files = convert_myhdl(
            fixed_multiply(*(signals[n] for n in MULTIPLY_ORDER), fmt), "mul", tmp_path
        )
    mapped = map_xc7(files[-1], "mul", tmp_path)
    assert mapped.dsp_registers == ({"AREG": 1, "BREG": 1, "MREG": 1, "PREG": 1},)
    # Only the rounding is left in the fabric: one register stage of flip-flops after the DSP.
    assert mapped.cells.get("FDRE", 0) <= fmt.width + MULTIPLY_LATENCY + 2


@block
def exact_with_handshake(clk, rst, in_valid, in_ready, a, b, out_valid, out_ready, product):
    """`exact_multiply` with its valid bit in a delay line beside it and one stall enable."""
    advance = Signal(bool(0))
    stages = exact_multiply_stages(len(a), len(b))
    a_reg, b_reg = Signal(a.val), Signal(b.val)
    valid_in = Signal(bool(0))
    operands = [
        stage_register(clk, rst, advance, source, target)
        for source, target in ((a, a_reg), (b, b_reg), (in_valid, valid_in))
    ]
    datapath = exact_multiply(clk, rst, advance, a_reg, b_reg, product)
    control = handshakes(clk, rst, valid_in, in_ready, out_valid, out_ready, advance, stages)
    return operands, datapath, control


@settings(max_examples=8)
@given(a_width=st.integers(2, 60), b_width=st.integers(2, 60), data=st.data())
def test_exact_multiply_gives_the_exact_product_under_backpressure(a_width, b_width, data):
    a_fmt, b_fmt = FixedFormat(a_width, 0), FixedFormat(b_width, 0)
    a_values = st.integers(a_fmt.min_raw, a_fmt.max_raw)
    b_values = st.integers(b_fmt.min_raw, b_fmt.max_raw)
    pairs = [(a_fmt.min_raw, b_fmt.min_raw), (a_fmt.max_raw, b_fmt.min_raw), (-1, -1)]
    pairs += data.draw(st.lists(st.tuples(a_values, b_values), min_size=1, max_size=15))
    signals = ports(a_fmt)
    signals.update(a=a_fmt.signal(), b=b_fmt.signal())
    signals["product"] = FixedFormat(a_width + b_width, 0).signal()
    run = simulate_stream(
        exact_with_handshake,
        [signals[n] for n in MULTIPLY_ORDER],
        signals,
        {"a": [a for a, _ in pairs], "b": [b for _, b in pairs]},
        ["product"],
        seed=data.draw(st.integers(0, 1000)),
    )
    assert run.outputs["product"] == [a * b for a, b in pairs]
    # the operand registers take the pair: the limb products and sums follow
    assert min(run.latencies) == exact_multiply_stages(a_width, b_width)


def test_a_wide_exact_product_keeps_every_dsp48_registered_and_the_path_short(tmp_path):
    fmt = FixedFormat(46, 44)  # the pipelined quaternion core's components
    signals = ports(fmt)
    signals["product"] = FixedFormat(92, 88).signal()
    with elaboration():
        files = convert_myhdl(
            exact_with_handshake(*(signals[n] for n in MULTIPLY_ORDER)), "exact", tmp_path
        )
    mapped = map_xc7(files[-1], "exact", tmp_path)
    assert len(mapped.dsp_registers) == 6  # 2 x 3 limbs of 24 x 17 bits
    assert all(r["MREG"] == 1 and r["PREG"] == 1 for r in mapped.dsp_registers)
    assert mapped.arrival_ps <= 5000  # half the period at 100 MHz


@pytest.mark.parametrize("width", [26, 46, 50])
def test_converted_exact_multiply_gives_the_exact_product(tmp_path, width):
    # at 26 and 50 bits the last sum is no wider than its first operand (the VHDL once lost
    # the shifted operand's top bits there)
    fmt = FixedFormat(width, 0)
    signals = ports(fmt)
    signals["product"] = FixedFormat(2 * width, 0).signal()
    with elaboration():
        files = convert_myhdl(
            exact_with_handshake(*(signals[n] for n in MULTIPLY_ORDER)), "exact", tmp_path / "hdl"
        )
    rng = np.random.default_rng(width)
    a = [fmt.min_raw, fmt.max_raw, -5, *raw_values(rng, fmt, 30).tolist()]
    b = [fmt.min_raw, fmt.min_raw, 7, *raw_values(rng, fmt, 30).tolist()]
    inputs = {"a": [unsigned(x, width) for x in a], "b": [unsigned(y, width) for y in b]}
    run = run_handshake(files, "exact", inputs, ["product"], tmp_path)
    got = [signed(v, 2 * width) for v in run.outputs["product"]]
    assert got == [x * y for x, y in zip(a, b, strict=True)]
