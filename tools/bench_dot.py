"""Benchmark: rfc.lib.arith's dot product at the image pipeline's and a few usual parameters.

For each parameter set: latency and initiation interval measured in MyHDL simulation (no idle
cycles, no backpressure), then LUT, FF and DSP48E1 and the critical path's cell delay from the
flow of tools/timing_table.py and `rfc build --estimate` (`rfc.toolchain.module_estimate`:
Yosys `synth_xilinx -family xc7 -abc9 -flatten` of the converted Verilog out of context, `sta`
with the 7-series cells' delays, no routing; estimated Fmax = 1 / (2 x cell delay)).
Prints the Markdown rows of docs/arithmetic.md's dot-product table.

Usage: RFC_CACHE_DIR=.cache .venv/bin/python tools/bench_dot.py
"""

from __future__ import annotations

import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from myhdl import ResetSignal, Signal

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the flat wrapper and the stream bench live under tests/

from rfc.lib.arith.dot_hdl import constant_dot, fixed_dot  # noqa: E402
from rfc.lib.fixed import FixedFormat  # noqa: E402
from rfc.toolchain import convert_myhdl, module_estimate, start_new_design  # noqa: E402
from rfc.toolchain.sta import ROUTING_FACTOR  # noqa: E402
from tests.lib.arith.flat import flat_ports, flat_top  # noqa: E402
from tests.support.myhdl_stream import simulate_stream  # noqa: E402


@dataclass(frozen=True)
class Case:
    """A dot product to measure: its terms, format and constant coefficients (or none)."""

    label: str
    terms: int
    fmt: FixedFormat
    coefficients: tuple[int, ...] | None = None


CASES = (
    Case("RgbToGray's luma: 3 constant terms, Q1.14", 3, FixedFormat(15, 14), (4899, 9617, 1868)),
    Case("3 terms, Q2.16", 3, FixedFormat(18, 16)),
    Case("4 terms, Q2.16", 4, FixedFormat(18, 16)),
    Case("4 terms, Q6.44", 4, FixedFormat(50, 44)),
)


def elaborate(case: Case):
    """The flat top level, its arguments in order and its ports by name."""
    signals = {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        "in_valid": Signal(bool(0)),
        "in_ready": Signal(bool(0)),
        "a": [case.fmt.signal() for _ in range(case.terms)],
        "b": [case.fmt.signal() for _ in range(case.terms)],
        "out_valid": Signal(bool(0)),
        "out_ready": Signal(bool(0)),
        "result": case.fmt.signal(),
    }
    if case.coefficients is None:
        block, extra, groups = fixed_dot, (case.fmt,), {"a": case.terms, "b": case.terms}
    else:
        block, extra, groups = constant_dot, (case.coefficients, case.fmt), {"a": case.terms}
        del signals["b"]
    order = tuple(signals)
    if case.coefficients is not None:
        order = (*order[:-1], "result")
    names = [f"{n}{i}" if n in groups else n for n in order for i in range(groups.get(n, 1))]
    ports = flat_ports(signals)
    return flat_top(block, order, groups, extra), [ports[n] for n in names], ports


def measure(case: Case, work: Path) -> str:
    top, arguments, ports = elaborate(case)
    inputs = {f"a{i}": list(range(1, 9)) for i in range(case.terms)}
    if case.coefficients is None:
        inputs.update({f"b{i}": list(range(8, 0, -1)) for i in range(case.terms)})
    run = simulate_stream(top, arguments, ports, inputs, ["result"], idle=0.0, backpressure=0.0)
    start_new_design()
    top, arguments, _ = elaborate(case)
    files = convert_myhdl(top(*arguments), "dot", work / case.label.replace(" ", "_"))
    estimate = module_estimate(files[-1], "dot")
    delay = estimate.timing.delay_ps / 1000 if estimate.timing else float("nan")
    cells = estimate.resources
    return (
        f"| {case.label} | {max(run.latencies)} | {int(min(np.diff(run.accepted)))} |"
        f" {cells.lut} | {cells.ff} | {cells.dsp} | {delay:.2f} ns |"
        f" {1e3 / (delay * ROUTING_FACTOR):.0f} MHz |"
    )


def main() -> None:
    print("| dot product | latency | II | LUT | FF | DSP48E1 | cell delay | est. Fmax |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory(prefix="rfc-bench-dot-") as scratch:
        for case in CASES:
            print(measure(case, Path(scratch)), flush=True)


if __name__ == "__main__":
    main()
