"""The shared engine through the 4x4 transform product: model against NumPy and exact sums,
the MyHDL block and its VHDL (flat ports, GHDL) against the model."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal

from rfc.lib.arith.engine import Op, ProgramBuilder, Step, run, schedule
from rfc.lib.arith.transform import transform_multiply, transform_program
from rfc.lib.fixed import FixedFormat
from rfc.toolchain import convert_myhdl
from tests.lib.arith.flat import flat_ports, flat_top
from tests.support.cosim import run_handshake, signed, unsigned
from tests.support.myhdl_stream import simulate_stream

WORD = FixedFormat(50, 44)
ORDER = ("clk", "rst", "in_valid", "in_ready", "a", "b", "out_valid", "out_ready", "c")
GROUPS = {"a": 12, "b": 12, "c": 12}


def rigid(rng: np.random.Generator, count: int) -> np.ndarray:
    """Random rotations (QR of Gaussian matrices) with translations up to 2: (count, 3, 4)."""
    q, r = np.linalg.qr(rng.normal(size=(count, 3, 3)))
    rotation = q * np.sign(np.diagonal(r, axis1=1, axis2=2))[:, None, :]
    return np.concatenate([rotation, rng.uniform(-2, 2, (count, 3, 1))], axis=2)


def to_raw(values: np.ndarray, fmt: FixedFormat) -> list[np.ndarray]:
    raw = np.rint(values.reshape(len(values), 12) * 2.0**fmt.frac_bits).astype(np.int64)
    return list(raw.T)


def test_products_within_one_unit_of_numpy_over_100k_pairs():
    rng = np.random.default_rng(1)
    a, b = rigid(rng, 100_000), rigid(rng, 100_000)
    raw_a, raw_b = to_raw(a, WORD), to_raw(b, WORD)
    got = np.array(run(transform_program(WORD), raw_a + raw_b), dtype=float).T / 2.0**44
    exact_a = np.array(raw_a, dtype=float).T.reshape(-1, 3, 4) / 2.0**44
    exact_b = np.array(raw_b, dtype=float).T.reshape(-1, 3, 4) / 2.0**44
    bottom = np.broadcast_to([0.0, 0.0, 0.0, 1.0], (100_000, 1, 4))
    want = (np.concatenate([exact_a, bottom], 1) @ np.concatenate([exact_b, bottom], 1))[:, :3]
    assert np.abs(got - want.reshape(-1, 12)).max() <= 2.0**-44


def test_each_entry_is_the_exact_sum_rounded_half_up():
    rng = np.random.default_rng(2)
    raw_a, raw_b = to_raw(rigid(rng, 300), WORD), to_raw(rigid(rng, 300), WORD)
    got = run(transform_program(WORD), raw_a + raw_b)
    for n in range(300):
        a = [[WORD.value(int(raw_a[4 * r + k][n])) for k in range(4)] for r in range(3)]
        b = [[WORD.value(int(raw_b[4 * r + k][n])) for k in range(4)] for r in range(3)]
        for r in range(3):
            for j in range(4):
                total = sum(a[r][k] * b[k][j] for k in range(3)) + (a[r][3] if j == 3 else 0)
                want = math.floor(total * 2**44 + Fraction(1, 2))
                assert got[4 * r + j][n] == want


def test_the_schedule_waits_for_sums_and_never_writes_twice_in_a_cycle():
    builder = ProgramBuilder(WORD)
    x = builder.load()
    square = builder.dot([(x, x)])
    builder.store(builder.dot([(square, x)]))
    steps = builder.build().steps
    ops = [s.op for s in steps]
    # load; square; 4 no-ops until the square is written; the product; 4 no-ops; store; done.
    assert ops == [Op.LOAD, Op.MAC, *[Op.NOP] * 4, Op.MAC, *[Op.NOP] * 4, Op.STORE, Op.DONE]
    clash = schedule(
        [Step(Op.MAC, 0, 0, 1, True, True), *[Step(Op.LOAD, dst=2 + i) for i in range(5)]]
    )
    assert [s.op for s in clash].count(Op.NOP) == 1  # the fifth load waits for the sum's write


def test_wrong_input_counts_and_long_sums_are_refused():
    with pytest.raises(ValueError, match="takes 24 inputs"):
        run(transform_program(WORD), [0] * 23)
    with pytest.raises(ValueError, match="1 to 16 products"):
        ProgramBuilder(WORD).dot([(0, 0)] * 17)


def ports(fmt: FixedFormat) -> dict:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "a": [fmt.signal() for _ in range(12)],
        "b": [fmt.signal() for _ in range(12)],
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "c": [fmt.signal() for _ in range(12)],
    }


def inputs_of(messages: list[list[int]]) -> dict[str, list[int]]:
    names = [f"a{i}" for i in range(12)] + [f"b{i}" for i in range(12)]
    return {name: [m[i] for m in messages] for i, name in enumerate(names)}


@settings(max_examples=5)
@given(st.data())
def test_myhdl_simulation_matches_the_model(data):
    width = data.draw(st.integers(8, 40))
    fmt = FixedFormat(width, data.draw(st.integers(2, width - 3)))
    value = st.integers(fmt.min_raw, fmt.max_raw)
    messages = data.draw(
        st.lists(st.lists(value, min_size=24, max_size=24), min_size=1, max_size=3)
    )
    flat = flat_ports(ports(fmt))
    run_ = simulate_stream(
        flat_top(transform_multiply, ORDER, GROUPS, [fmt]),
        list(flat.values()),
        flat,
        inputs_of(messages),
        [f"c{i}" for i in range(12)],
        seed=data.draw(st.integers(0, 1000)),
    )
    program = transform_program(fmt)
    got = [[run_.outputs[f"c{i}"][n] for i in range(12)] for n in range(len(messages))]
    assert got == [run(program, m) for m in messages]
    assert set(run_.latencies) == {program.cycles}


def test_converted_vhdl_with_flat_ports_matches_the_model(tmp_path):
    rng = np.random.default_rng(3)
    raw = to_raw(rigid(rng, 8), WORD) + to_raw(rigid(rng, 8), WORD)
    messages = [[int(column[n]) for column in raw] for n in range(8)]
    top = flat_top(transform_multiply, ORDER, GROUPS, [WORD])
    files = convert_myhdl(top(**flat_ports(ports(WORD))), "transform", tmp_path / "hdl")
    inputs = {k: [unsigned(v, 50) for v in values] for k, values in inputs_of(messages).items()}
    result = run_handshake(files, "transform", inputs, [f"c{i}" for i in range(12)], tmp_path)
    program = transform_program(WORD)
    got = [[signed(result.outputs[f"c{i}"][n], 50) for i in range(12)] for n in range(8)]
    assert got == [run(program, m) for m in messages]
    assert set(result.latencies) == {program.cycles}
