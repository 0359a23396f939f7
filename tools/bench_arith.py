"""Benchmark: rfc.lib.arith's blocks and the Franka forward-kinematics core.

For each block: latency and initiation interval measured in MyHDL simulation (no idle cycles,
no backpressure), LUT/FF/DSP from Yosys (`synth_xilinx -family xc7`, through GHDL's synthesis
of the converted VHDL), the critical path's cell delay from Yosys' `sta` after
`synth_xilinx -abc9 -flatten` of the converted Verilog (no routing), and accuracy of the
bit-exact model (which the tests prove equal to the hardware) against NumPy float64 over many
random inputs.

Usage: .venv/bin/python tools/bench_arith.py [--samples N] [--states N] [--no-synth]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from myhdl import ResetSignal, Signal, intbv

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the stream bench and flat wrappers live under tests/

from rfc.lib.arith import SinCosConfig, sincos  # noqa: E402
from rfc.lib.arith.convert_hdl import (  # noqa: E402
    fixed_to_float_pipelined,
    float_to_fixed_pipelined,
)
from rfc.lib.arith.engine import run  # noqa: E402
from rfc.lib.arith.mac import multiply, multiply_accumulate  # noqa: E402
from rfc.lib.arith.mac_hdl import fixed_mac, fixed_multiply  # noqa: E402
from rfc.lib.arith.sincos_hdl import sincos as sincos_block  # noqa: E402
from rfc.lib.arith.transform import transform_multiply, transform_program  # noqa: E402
from rfc.lib.cordic import CordicConfig  # noqa: E402
from rfc.lib.cordic.hdl import cordic_vectoring  # noqa: E402
from rfc.lib.fixed import FixedFormat  # noqa: E402
from rfc.toolchain import convert_myhdl, estimate_resources, start_new_design  # noqa: E402
from tests.examples.franka_fk.example import load, states, to_bits, to_float  # noqa: E402
from tests.lib.arith.flat import flat_ports, flat_top  # noqa: E402
from tests.lib.arith.synth import map_xc7  # noqa: E402
from tests.support.myhdl_stream import simulate_stream  # noqa: E402

WORD = FixedFormat(50, 44)
#: The pipelined quaternion core's CORDIC (examples/quaternion_to_euler).
VECTORING = CordicConfig(width=50, iterations=38, angle_frac=46)
DSP_WORD = FixedFormat(18, 16)  # fits one DSP48E1 multiplier (25 x 18)


def handshake(**data: Signal) -> dict[str, Any]:
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        **data,
    }


@dataclass(frozen=True)
class Case:
    """A block to measure: how to build it flat, and a few inputs to stream through it."""

    name: str
    function: Callable[..., Any]
    order: tuple[str, ...]
    ports: Callable[[], dict[str, Any]]
    extra: tuple[Any, ...]
    inputs: dict[str, list[int]]
    output: str
    groups: dict[str, int] | None = None


def cases() -> list[Case]:
    sc_order = ("clk", "rst", "in_valid", "in_ready", "angle", "out_valid", "out_ready", "cos",
                "sin")  # fmt: skip
    mul_order = ("clk", "rst", "in_valid", "in_ready", "a", "b", "out_valid", "out_ready",
                 "product")  # fmt: skip
    mac_order = ("clk", "rst", "in_valid", "in_ready", "a", "b", "first", "out_valid",
                 "out_ready", "total")  # fmt: skip
    config = SinCosConfig(44)

    def sc_ports() -> dict[str, Any]:
        return handshake(
            angle=config.angle_format.signal(),
            cos=config.out_format.signal(),
            sin=config.out_format.signal(),
        )

    def mul_ports(fmt: FixedFormat) -> Callable[[], dict[str, Any]]:
        return lambda: handshake(
            a=fmt.signal(), b=fmt.signal(), first=Signal(bool(0)), product=fmt.signal(),
            total=fmt.signal(),
        )  # fmt: skip

    def conv_ports() -> dict[str, Any]:
        return handshake(
            bits=Signal(intbv(0)[64:]),
            raw=WORD.signal(),
            overflow=Signal(bool(0)),
            invalid=Signal(bool(0)),
        )

    def transform_ports() -> dict[str, Any]:
        return handshake(
            a=[WORD.signal() for _ in range(12)],
            b=[WORD.signal() for _ in range(12)],
            c=[WORD.signal() for _ in range(12)],
        )

    def fk_ports() -> dict[str, Any]:
        def word() -> Signal:
            return Signal(intbv(0)[64:])

        return handshake(
            q=[word() for _ in range(7)],
            f_t_ee=[word() for _ in range(16)],
            o_t_ee=[word() for _ in range(16)],
            transforms=[word() for _ in range(112)],
            mse=word(),
        )

    def cordic_ports() -> dict[str, Any]:
        def signed(bits: int) -> Signal:
            return Signal(intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1)))

        return handshake(
            x=signed(VECTORING.width),
            y=signed(VECTORING.width),
            angle=signed(VECTORING.angle_width),
            magnitude=Signal(intbv(0)[VECTORING.magnitude_width :]),
        )

    cordic_order = ("clk", "rst", "in_valid", "in_ready", "x", "y", "out_valid", "out_ready",
                    "angle", "magnitude")  # fmt: skip
    vectors = {"x": [5, -6, 7, 0, 9, 1], "y": [1, 2, -3, 0, 4, -8]}
    angles = {"angle": [1, -2, 3, 4, 5, 6]}
    pairs = {"a": [1, 2, 3, 4, 5, 6], "b": [6, 5, 4, 3, 2, 1]}
    transform_in = {f"{g}{i}": [i + 1] * 3 for g in "ab" for i in range(12)}
    q, f_t_ee, o_t_ee = states(2, seed=1)
    fk_in = {}
    for name, values in (("q", q), ("f_t_ee", f_t_ee), ("o_t_ee", o_t_ee)):
        fk_in.update(
            {f"{name}{i}": [int(v) for v in to_bits(values[:, i])] for i in range(len(values[0]))}
        )
    fk_order = ("clk", "rst", "q", "f_t_ee", "o_t_ee", "in_valid", "in_ready", "transforms",
                "mse", "out_valid", "out_ready")  # fmt: skip
    transform_order = ("clk", "rst", "in_valid", "in_ready", "a", "b", "out_valid", "out_ready",
                       "c")  # fmt: skip
    return [
        Case("sincos iterative (Q4.44)", sincos_block, sc_order, sc_ports, (config, False),
             angles, "cos"),
        Case("sincos pipelined (Q4.44)", sincos_block, sc_order, sc_ports, (config, True),
             angles, "cos"),
        Case("CORDIC vectoring iterative (50 bits, 38 iterations)", cordic_vectoring,
             cordic_order, cordic_ports, (VECTORING, False), vectors, "angle"),
        Case("CORDIC vectoring pipelined (50 bits, 38 stages)", cordic_vectoring, cordic_order,
             cordic_ports, (VECTORING, True), vectors, "angle"),
        Case("multiply Q2.16", fixed_multiply, mul_order, mul_ports(DSP_WORD), (DSP_WORD,),
             pairs, "product"),
        Case("multiply Q6.44", fixed_multiply, mul_order, mul_ports(WORD), (WORD,), pairs,
             "product"),
        Case("multiply-accumulate Q6.44", fixed_mac, mac_order, mul_ports(WORD), (WORD,),
             {**pairs, "first": [1, 0, 0, 1, 0, 0]}, "total"),
        Case("float64 → Q6.44 pipelined", float_to_fixed_pipelined,
             ("clk", "rst", "in_valid", "in_ready", "bits", "out_valid", "out_ready", "raw",
              "overflow", "invalid"), conv_ports, (WORD,), {"bits": [1, 2, 3, 4, 5]}, "raw"),
        Case("Q6.44 → float64 pipelined", fixed_to_float_pipelined,
             ("clk", "rst", "in_valid", "in_ready", "raw", "out_valid", "out_ready", "bits"),
             conv_ports, (WORD,), {"raw": [1, 2, 3, 4, 5]}, "bits"),
        Case("4x4 transform product Q6.44", transform_multiply, transform_order,
             transform_ports, (WORD,), transform_in, "c0", {"a": 12, "b": 12, "c": 12}),
        Case("Franka FK core", load("fk_core").fk_core, fk_order, fk_ports, (), fk_in, "mse",
             {"q": 7, "f_t_ee": 16, "o_t_ee": 16, "transforms": 112}),
    ]  # fmt: skip


def measure(case: Case, work: Path, synth: bool) -> str:
    groups = case.groups or {}
    names = [f"{n}{i}" if n in groups else n for n in case.order for i in range(groups.get(n, 1))]
    ports = flat_ports(case.ports())
    top = flat_top(case.function, case.order, groups, case.extra)
    arguments = [ports[n] for n in names]
    run_ = simulate_stream(
        top, arguments, ports, case.inputs, [case.output], idle=0.0, backpressure=0.0
    )
    latency = max(run_.latencies)
    interval = int(min(np.diff(run_.accepted)))
    row = f"| {case.name} | {latency} | {interval} |"
    if synth:
        start_new_design()
        ports = flat_ports(case.ports())
        name = "top_" + "_".join("".join(c for c in w if c.isalnum()) for w in case.name.split())
        name = "_".join(part for part in name.lower().split("_") if part)
        files = convert_myhdl(top(*(ports[n] for n in names)), name, work / name)
        start = time.perf_counter()
        cells = estimate_resources(files[:-1], name)
        timing = map_xc7(files[-1], name, work / name)
        seconds = time.perf_counter() - start
        row += (
            f" {cells.lut} | {cells.ff} | {cells.dsp} | {cells.lutram} |"
            f" {timing.arrival_ps / 1000:.2f} ns ({timing.fmax_mhz:.0f} MHz) | ({seconds:.0f} s)"
        )
    return row


def accuracy(samples: int, fk_states: int) -> None:
    rng = np.random.default_rng(1)
    config = SinCosConfig(44)
    angle = rng.uniform(-2 * np.pi, 2 * np.pi, samples)
    cos, sin = sincos(np.rint(angle * 2.0**44).astype(np.int64), config)
    error = max(
        np.abs(cos / 2.0**44 - np.cos(angle)).max(), np.abs(sin / 2.0**44 - np.sin(angle)).max()
    )
    print(f"sincos Q4.44, float64 angles in [-2π, 2π]: max |error| {error:.2e} ({samples} angles)")

    a = rng.integers(-(1 << 46), 1 << 46, samples)  # [-4, 4): products stay inside Q6.44
    b = rng.integers(-(1 << 46), 1 << 46, samples)
    product = multiply(a.astype(object), b.astype(object), WORD).astype(float) / 2.0**44
    want = (a / 2.0**44) * (b / 2.0**44)
    print(f"multiply Q6.44: max |error| {np.abs(product - want).max():.2e} (half a unit 2.8e-14)")

    def operand() -> np.ndarray:
        return rng.integers(-(1 << 45), 1 << 45, samples).astype(object)  # [-2, 2)

    terms = [(operand(), operand()) for _ in range(16)]
    total = multiply_accumulate(terms, WORD).astype(float) / 2.0**44
    exact = sum((x.astype(float) / 2.0**44) * (y.astype(float) / 2.0**44) for x, y in terms)
    print(f"multiply-accumulate Q6.44, 16 products: max |error| {np.abs(total - exact).max():.2e}")

    rotation, _ = np.linalg.qr(rng.normal(size=(samples, 3, 3)))
    rigid = np.concatenate([rotation, rng.uniform(-2, 2, (samples, 3, 1))], axis=2)
    raw = np.rint(rigid.reshape(samples, 12) * 2.0**44).astype(np.int64)
    left, right = raw, np.roll(raw, 1, axis=0)
    got = np.array(run(transform_program(WORD), list(left.T) + list(right.T)), dtype=float).T
    bottom = np.broadcast_to([0.0, 0.0, 0.0, 1.0], (samples, 1, 4))
    full = lambda m: np.concatenate([m.reshape(-1, 3, 4) / 2.0**44, bottom], 1)  # noqa: E731
    want = (full(left) @ full(right))[:, :3].reshape(samples, 12)
    print(f"transform product Q6.44: max |error| {np.abs(got / 2.0**44 - want).max():.2e}")

    q, f_t_ee, o_t_ee = states(fk_states, seed=7)
    start = time.perf_counter()
    transforms, mse = load("fk_core").fk_model(
        list(to_bits(q).T), list(to_bits(f_t_ee).T), list(to_bits(o_t_ee).T)
    )
    want_t, want_mse = load("reference").forward_kinematics(q, f_t_ee, o_t_ee)
    got_t = np.array([to_float(np.asarray(c)) for c in transforms]).T
    mse_error = np.abs(to_float(np.asarray(mse)) - want_mse).max()
    print(
        f"Franka FK vs NumPy ({fk_states} states in the joint limits): max |error| transforms "
        f"{np.abs(got_t - want_t).max():.2e}, mse {mse_error:.2e}"
        f"  ({time.perf_counter() - start:.0f} s)"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1_000_000, help="random inputs per block")
    parser.add_argument("--states", type=int, default=10_000, help="random robot states")
    parser.add_argument("--no-synth", action="store_true", help="skip Yosys")
    parser.add_argument("--only", help="measure only blocks whose name contains this")
    args = parser.parse_args()
    header = "| block | latency | II |"
    if not args.no_synth:
        header += " LUT | FF | DSP48E1 | LUTRAM | cell delay (Fmax) | |"
    print(header)
    with tempfile.TemporaryDirectory(prefix="rfc-bench-arith-") as scratch:
        for case in cases():
            if args.only and args.only not in case.name:
                continue
            print(measure(case, Path(scratch), not args.no_synth), flush=True)
    accuracy(args.samples, args.states)


if __name__ == "__main__":
    main()
