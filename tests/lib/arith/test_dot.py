"""Dot product: the model against NumPy and exact integers, the blocks against the model in
MyHDL and GHDL, and the product registers as Yosys maps them."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal

from rfc.lib.arith.dot import dot_latency, dot_product
from rfc.lib.arith.dot_hdl import constant_dot, fixed_dot
from rfc.lib.fixed import FixedFormat
from rfc.toolchain import convert_myhdl, elaboration
from tests.lib.arith.flat import flat_ports, flat_top
from tests.lib.arith.synth import map_xc7
from tests.support.cosim import run_handshake, signed, unsigned
from tests.support.myhdl_stream import simulate_stream

#: The image pipeline's: 8-bit pixels and BT.601 weights as raw Q1.14 integers.
LUMA = FixedFormat(15, 14)
LUMA_WEIGHTS = (4899, 9617, 1868)
WIDE = FixedFormat(50, 44)
FIXED_ORDER = ("clk", "rst", "in_valid", "in_ready", "a", "b", "out_valid", "out_ready", "result")
CONSTANT_ORDER = ("clk", "rst", "in_valid", "in_ready", "a", "out_valid", "out_ready", "result")


def extreme_values(rng: np.random.Generator, fmt: FixedFormat, count: int) -> np.ndarray:
    """Raw integers of `fmt` over all magnitudes, a tenth of them the format's ends (objects)."""
    top = np.int64(1) << rng.integers(0, fmt.width - 1, count)
    values = np.clip(rng.integers(-top, top), fmt.min_raw, fmt.max_raw)
    ends = rng.random(count) < 0.1
    values[ends] = rng.choice([fmt.min_raw, fmt.max_raw], ends.sum())
    return values.astype(object)


def test_narrow_model_equals_numpy_over_100k_vectors():
    """Q1.14 sums of three products fit float64 exactly: NumPy's floor(x + 1/2) is the oracle."""
    rng = np.random.default_rng(11)
    a = [extreme_values(rng, LUMA, 100_000) for _ in range(3)]
    b = [extreme_values(rng, LUMA, 100_000) for _ in range(3)]
    got = dot_product(a, b, LUMA).astype(np.int64)
    exact = sum(x.astype(np.int64) * y.astype(np.int64) for x, y in zip(a, b, strict=True))
    want = np.clip(np.floor(exact / 2.0**14 + 0.5), LUMA.min_raw, LUMA.max_raw)
    assert np.array_equal(got, want.astype(np.int64))
    saturated = (got == LUMA.min_raw) | (got == LUMA.max_raw)
    assert saturated.sum() > 1000  # both kinds are covered
    assert saturated.mean() < 0.5


def test_gray_weights_give_opencvs_integer_luma_for_every_byte_triple_sampled():
    rng = np.random.default_rng(12)
    rgb = rng.integers(0, 256, (3, 100_000))
    rgb[:, :8] = [[0, 255, 255, 0, 0, 255, 1, 128]] * 3
    got = dot_product(list(rgb.astype(object)), LUMA_WEIGHTS, LUMA)
    want = (4899 * rgb[0] + 9617 * rgb[1] + 1868 * rgb[2] + 8192) >> 14
    assert np.array_equal(got.astype(np.int64), want)


def test_wide_model_rounds_the_exact_sum_half_up_over_100k_vectors():
    """Beyond float64: r is the rounding of s when (2r - 1)·2**(f-1) <= s < (2r + 1)·2**(f-1)."""
    rng = np.random.default_rng(13)
    a = [extreme_values(rng, WIDE, 100_000) for _ in range(5)]
    b = [extreme_values(rng, WIDE, 100_000) for _ in range(5)]
    got = dot_product(a, b, WIDE)
    total = sum(int_a * int_b for int_a, int_b in zip(a, b, strict=True))
    half = 1 << (WIDE.frac_bits - 1)
    inside = (got > WIDE.min_raw) & (got < WIDE.max_raw)
    assert np.all(((2 * got - 1) * half <= total)[inside])
    assert np.all((total < (2 * got + 1) * half)[inside])
    assert np.all((total >= (2 * got - 1) * half)[got == WIDE.max_raw])
    assert np.all((total < (2 * got + 1) * half)[got == WIDE.min_raw])
    assert (~inside).sum() > 1000
    assert inside.mean() > 0.5


def test_a_single_python_vector_is_rounded_half_up():
    fmt = FixedFormat(8, 2)
    assert dot_product([1, 1], [1, 1], fmt) == 1  # 2/16 = 0.125 units of 1/4: 0.5 rounds up
    assert dot_product([-1, 0], [2, 0], fmt) == 0  # -2/16 = -0.5 units rounds up to 0
    assert dot_product([127, 127], [127, 127], fmt) == fmt.max_raw


def test_lists_of_different_lengths_are_refused():
    with pytest.raises(ValueError, match="equal, non-empty"):
        dot_product([1, 2], [3], LUMA)


def ports(fmt: FixedFormat, terms: int) -> dict:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "a": [fmt.signal() for _ in range(terms)],
        "b": [fmt.signal() for _ in range(terms)],
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "result": fmt.signal(),
    }


def flat(fmt: FixedFormat, terms: int, coefficients: tuple[int, ...] | None):
    """The block with one port per signal, its arguments, and its ports by flat name."""
    signals = ports(fmt, terms)
    if coefficients is None:
        order, groups, extra, block = FIXED_ORDER, {"a": terms, "b": terms}, (fmt,), fixed_dot
    else:
        order, groups, extra = CONSTANT_ORDER, {"a": terms}, (coefficients, fmt)
        block = constant_dot
    names = [f"{n}{i}" if n in groups else n for n in order for i in range(groups.get(n, 1))]
    by_name = flat_ports({n: signals[n] for n in order})
    return flat_top(block, order, groups, extra), [by_name[n] for n in names], by_name


@settings(max_examples=8, deadline=None)
@given(terms=st.integers(1, 6), width=st.integers(4, 40), constant=st.booleans(), data=st.data())
def test_myhdl_blocks_match_the_model_under_random_valid_and_ready(terms, width, constant, data):
    fmt = FixedFormat(width, data.draw(st.integers(1, width)))
    value = st.integers(fmt.min_raw, fmt.max_raw)
    vectors = data.draw(st.lists(st.lists(value, min_size=terms, max_size=terms), min_size=1,
                                 max_size=20))  # fmt: skip
    vectors.insert(0, [fmt.max_raw] * terms)  # saturation
    seconds = data.draw(st.lists(value, min_size=terms, max_size=terms))
    coefficients = tuple(seconds) if constant else None
    top, arguments, by_name = flat(fmt, terms, coefficients)
    inputs = {f"a{i}": [v[i] for v in vectors] for i in range(terms)}
    if constant:
        want = [dot_product(v, coefficients, fmt) for v in vectors]
    else:
        inputs.update({f"b{i}": [v[terms - 1 - i] for v in vectors] for i in range(terms)})
        want = [dot_product(v, v[::-1], fmt) for v in vectors]
    run = simulate_stream(
        top, arguments, by_name, inputs, ["result"], seed=data.draw(st.integers(0, 1000))
    )
    assert run.outputs["result"] == want
    assert min(run.latencies) == dot_latency(terms)


@pytest.mark.parametrize("terms", [1, 3, 4])
def test_a_vector_every_cycle(terms):
    top, arguments, by_name = flat(LUMA, terms, LUMA_WEIGHTS[:1] * terms)
    inputs = {f"a{i}": list(range(10)) for i in range(terms)}
    run = simulate_stream(top, arguments, by_name, inputs, ["result"], idle=0.0, backpressure=0.0)
    assert set(np.diff(run.accepted)) == {1}
    assert max(run.latencies) == dot_latency(terms)


@pytest.mark.parametrize("constant", [False, True], ids=["fixed_dot", "constant_dot"])
def test_converted_vhdl_matches_the_model_under_backpressure(tmp_path, constant):
    rng = np.random.default_rng(14)
    terms = 3
    a = [extreme_values(rng, WIDE, 60).tolist() for _ in range(terms)]
    b = [extreme_values(rng, WIDE, 60).tolist() for _ in range(terms)]
    coefficients = (WIDE.max_raw, -(1 << 43), WIDE.min_raw) if constant else None
    top, arguments, _ = flat(WIDE, terms, coefficients)
    with elaboration():
        files = convert_myhdl(top(*arguments), "dot", tmp_path / "hdl")
    inputs = {f"a{i}": [unsigned(x, WIDE.width) for x in a[i]] for i in range(terms)}
    if constant:
        want = [dot_product(v, coefficients, WIDE) for v in zip(*a, strict=True)]
    else:
        inputs.update({f"b{i}": [unsigned(x, WIDE.width) for x in b[i]] for i in range(terms)})
        want = [
            dot_product(u, v, WIDE) for u, v in zip(zip(*a, strict=True), zip(*b, strict=True),
                                                    strict=True)
        ]  # fmt: skip
    run = run_handshake(files[:-1], "dot", inputs, ["result"], tmp_path)
    assert [signed(v, WIDE.width) for v in run.outputs["result"]] == want
    assert min(run.latencies) == dot_latency(terms)


def test_gray_weights_map_to_three_registered_dsp48s_within_half_a_100_mhz_period(tmp_path):
    top, arguments, _ = flat(LUMA, 3, LUMA_WEIGHTS)
    with elaboration():
        files = convert_myhdl(top(*arguments), "gray", tmp_path)
    mapped = map_xc7(files[-1], "gray", tmp_path)  # Yosys reads the Verilog
    assert len(mapped.dsp_registers) == 3
    # the operand (A) and product (M) registers sit in the slices; B is the constant
    assert all(r["AREG"] == r["MREG"] == 1 for r in mapped.dsp_registers)
    assert mapped.arrival_ps <= 5000  # half the period at 100 MHz


@pytest.mark.parametrize(
    ("coefficients", "message"),
    [((1 << 14, 0, 0), "outside the format"), ((1, 2), "need as many coefficients")],
)
def test_coefficients_outside_the_format_or_miscounted_are_refused(coefficients, message):
    signals = ports(LUMA, 3)
    with pytest.raises(ValueError, match=message):
        constant_dot(*(signals[n] for n in CONSTANT_ORDER), coefficients, LUMA)
