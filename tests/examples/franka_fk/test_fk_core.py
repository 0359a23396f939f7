"""The forward-kinematics core: its model against NumPy, MyHDL and GHDL against its model."""

from __future__ import annotations

import numpy as np
import pytest
from myhdl import ResetSignal, Signal, intbv

from rfc.toolchain import convert_myhdl, elaboration
from tests.examples.franka_fk.example import load, states, to_bits, to_float
from tests.lib.arith.flat import flat_ports, flat_top
from tests.support.cosim import run_handshake
from tests.support.myhdl_stream import simulate_stream

ORDER = ("clk", "rst", "q", "f_t_ee", "o_t_ee", "in_valid", "in_ready", "transforms", "mse",
         "out_valid", "out_ready")  # fmt: skip
GROUPS = {"q": 7, "f_t_ee": 16, "o_t_ee": 16, "transforms": 112}


def core_ports() -> dict:
    def word() -> Signal:
        return Signal(intbv(0)[64:])

    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "q": [word() for _ in range(7)],
        "f_t_ee": [word() for _ in range(16)],
        "o_t_ee": [word() for _ in range(16)],
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "transforms": [word() for _ in range(112)],
        "mse": word(),
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
    }


def flat_inputs(count: int, seed: int) -> dict[str, list[int]]:
    q, f_t_ee, o_t_ee = states(count, seed)
    inputs = {}
    for name, values in (("q", q), ("f_t_ee", f_t_ee), ("o_t_ee", o_t_ee)):
        inputs.update(
            {f"{name}{i}": [int(v) for v in to_bits(values[:, i])] for i in range(GROUPS[name])}
        )
    return inputs


def expected(inputs: dict[str, list[int]]) -> dict[str, list[int]]:
    core = load("fk_core")
    columns = {
        name: [np.array(inputs[f"{name}{i}"], dtype=object) for i in range(GROUPS[name])]
        for name in ("q", "f_t_ee", "o_t_ee")
    }
    transforms, mse = core.fk_model(columns["q"], columns["f_t_ee"], columns["o_t_ee"])
    out = {f"transforms{i}": [int(v) for v in values] for i, values in enumerate(transforms)}
    out["mse"] = [int(v) for v in mse]
    return out


def test_model_matches_numpy_within_1e9_over_random_states():
    q, f_t_ee, o_t_ee = states(3000, seed=11)
    transforms, mse = load("fk_core").fk_model(
        list(to_bits(q).T), list(to_bits(f_t_ee).T), list(to_bits(o_t_ee).T)
    )
    want_transforms, want_mse = load("reference").forward_kinematics(q, f_t_ee, o_t_ee)
    got = np.array([to_float(np.asarray(column)) for column in transforms]).T
    assert np.abs(got - want_transforms).max() <= 1e-9
    assert np.abs(to_float(np.asarray(mse)) - want_mse).max() <= 1e-9
    assert want_mse.max() > 1e-8  # the perturbation shows: the mse is not trivially 0


def test_myhdl_simulation_matches_the_model():
    inputs = flat_inputs(2, seed=3)
    ports = core_ports()
    flat = flat_ports(ports)
    run = simulate_stream(
        flat_top(load("fk_core").fk_core, ORDER, GROUPS),
        [flat[name] for name in flat],
        flat,
        inputs,
        [*(f"transforms{i}" for i in range(112)), "mse"],
    )
    assert run.outputs == expected(inputs)
    assert set(run.latencies) == {load("fk_core").fk_program().cycles}


@pytest.mark.slow
def test_converted_vhdl_with_flat_ports_matches_the_model(tmp_path):
    inputs = flat_inputs(3, seed=5)
    ports = flat_ports(core_ports())
    top = flat_top(load("fk_core").fk_core, ORDER, GROUPS)
    with elaboration():  # MyHDL alone reads the source context of every caller: minutes here
        files = convert_myhdl(top(**ports), "fk_core", tmp_path / "hdl", verilog=False)
    want = expected(inputs)
    run = run_handshake(files, "fk_core", inputs, list(want), tmp_path, expected=want)
    assert run.outputs == want
    assert set(run.latencies) == {load("fk_core").fk_program().cycles}
