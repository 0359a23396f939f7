"""The shared engine through the 4x4 transform product: model against NumPy and exact sums,
the MyHDL block and its VHDL (flat ports, GHDL) against the model; a float64 engine with every
unit, in MyHDL against the model and mapped by Yosys against the clock; the result bits the
output chain leaves out against Python's float64."""

from __future__ import annotations

import math
import struct
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal, intbv

from rfc.lib.arith import SinCosConfig
from rfc.lib.arith.engine import (
    Latencies,
    Op,
    Program,
    ProgramBuilder,
    Step,
    latencies,
    run,
    schedule,
)
from rfc.lib.arith.engine_hdl import engine, zero_result_bits
from rfc.lib.arith.transform import transform_multiply, transform_program
from rfc.lib.fixed import FixedFormat, bits_to_float, float_to_bits
from rfc.toolchain import convert_myhdl, elaboration, module_estimate
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
    # load; square; no-ops until the square is written; the product; no-ops; store; done.
    wait = [Op.NOP] * latencies(WORD, float_io=False).mac
    assert ops == [Op.LOAD, Op.MAC, *wait, Op.MAC, *wait, Op.STORE, Op.DONE]
    delays = Latencies(load=0, mac=4, store=0)
    clash = schedule(
        [Step(Op.MAC, 0, 0, 1, True, True), *[Step(Op.LOAD, dst=2 + i) for i in range(5)]], delays
    )
    assert [s.op for s in clash].count(Op.NOP) == 1  # the fifth load waits for the sum's write


def test_the_schedule_waits_for_pipelined_loads_and_stores_before_done():
    delays = Latencies(load=5, mac=4, store=3)
    steps = [Step(Op.LOAD, dst=0), Step(Op.MAC, 0, 0, 1, True, True), Step(Op.STORE, a=1)]
    ops = [s.op for s in schedule([*steps, Step(Op.DONE)], delays)]
    # the load's word is written on cycle 5, the sum issued on 6 and written on 10, the store
    # issued on 11 lands on 14, when DONE may end the message
    assert ops == [Op.LOAD, *[Op.NOP] * 5, Op.MAC, *[Op.NOP] * 4, Op.STORE, *[Op.NOP] * 2, Op.DONE]


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
    with elaboration():
        files = convert_myhdl(top(**flat_ports(ports(WORD))), "transform", tmp_path / "hdl")
    inputs = {k: [unsigned(v, 50) for v in values] for k, values in inputs_of(messages).items()}
    result = run_handshake(files, "transform", inputs, [f"c{i}" for i in range(12)], tmp_path)
    program = transform_program(WORD)
    got = [[signed(result.outputs[f"c{i}"][n], 50) for i in range(12)] for n in range(8)]
    assert got == [run(program, m) for m in messages]
    assert set(result.latencies) == {program.cycles}


def rotation_program() -> Program:
    """Float64 in and out through every unit: (x, y) turned by an angle, and the angle's cosine."""
    builder = ProgramBuilder(WORD, float_io=True, sincos=SinCosConfig(WORD.frac_bits))
    angle, x, y = builder.load(), builder.load(), builder.load()
    cos, sin = builder.cos_sin(angle)
    minus_one = builder.constant(-(1 << WORD.frac_bits))
    minus_sin = builder.dot([(sin, minus_one)])
    builder.store(builder.dot([(cos, x), (minus_sin, y)]))
    builder.store(builder.dot([(sin, x), (cos, y)]))
    builder.store(cos)
    return builder.build()


ENGINE_ORDER = ("clk", "rst", "in_valid", "in_ready", "inputs", "out_valid", "out_ready",
                "outputs")  # fmt: skip


def float_engine_ports() -> dict:
    def word() -> Signal:
        return Signal(intbv(0)[64:])

    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "inputs": [word() for _ in range(3)],
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "outputs": [word() for _ in range(3)],
    }


def test_a_float_engine_with_every_unit_matches_the_model_and_numpy():
    program = rotation_program()
    rng = np.random.default_rng(5)
    values = [(a, x, y) for a, x, y in rng.uniform(-3, 3, (4, 3))]
    messages = [[float_to_bits(float(v)) for v in m] for m in values]
    flat = flat_ports(float_engine_ports())
    run_ = simulate_stream(
        flat_top(engine, ENGINE_ORDER, {"inputs": 3, "outputs": 3}, [program]),
        list(flat.values()),
        flat,
        {f"inputs{i}": [m[i] for m in messages] for i in range(3)},
        [f"outputs{i}" for i in range(3)],
    )
    got = [[run_.outputs[f"outputs{i}"][n] for i in range(3)] for n in range(len(messages))]
    assert got == [run(program, m) for m in messages]
    assert set(run_.latencies) == {program.cycles}
    for (a, x, y), bits in zip(values, got, strict=True):
        want = (x * np.cos(a) - y * np.sin(a), x * np.sin(a) + y * np.cos(a), np.cos(a))
        assert np.allclose([bits_to_float(b) for b in bits], want, rtol=0, atol=1e-12)


@pytest.mark.slow
def test_a_float_engine_meets_100_mhz_with_margin(tmp_path):
    # the Franka core's engine with every unit: Q6.44 words, the float64 converters, the
    # multiply-accumulate, the iterative sine/cosine fed from the engine's registers, the ROM
    # and the memory; at most half a 100 MHz period of cell delay, with margin
    flat = flat_ports(float_engine_ports())
    top = flat_top(engine, ENGINE_ORDER, {"inputs": 3, "outputs": 3}, [rotation_program()])
    with elaboration():
        files = convert_myhdl(top(**flat), "engine", tmp_path)
    timing = module_estimate(files[-1], "engine").timing  # what `--estimate` reports of it
    assert timing is not None
    assert timing.delay_ps <= 4800


@given(st.data())
def test_the_result_bits_the_output_chain_leaves_out_are_zero_in_every_float64(data):
    # the output chain carries only a result's high bits and appends zeros: those must be zero
    # in Python's own float64 of every value of the format, its extremes included
    width = data.draw(st.integers(2, 64))
    fmt = FixedFormat(width, data.draw(st.integers(0, width - 1)))
    builder = ProgramBuilder(fmt, float_io=True)
    builder.store(builder.load())
    zeros = zero_result_bits(builder.build())
    raws = [
        fmt.min_raw,
        fmt.max_raw,
        -1,
        1,
        *data.draw(st.lists(st.integers(fmt.min_raw, fmt.max_raw))),
    ]
    for raw in raws:
        (bits,) = struct.unpack("<Q", struct.pack("<d", float(Fraction(raw, 1 << fmt.frac_bits))))
        assert bits & ((1 << zeros) - 1) == 0
    assert zeros == max(53 - width, 0)
