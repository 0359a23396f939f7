"""Measure rfc.lib's arithmetic blocks for `rfc check`: cell delay and cells per parameter set.

Each block is converted to Verilog at the parameters listed here (those of the examples and a
few usual ones), mapped out of context by `rfc.toolchain.module_estimate` (Yosys
`synth_xilinx -family xc7 -abc9 -flatten`, then `sta` with the 7-series cells' delays, no
routing) and written to lib/arith/timing.json under the key `rfc.lib.arith.timing.blocks_in`
gives it, which is the key `rfc check` looks up. Combinational blocks are timed between an
input and an output register. Prints a Markdown table (docs/arithmetic.md).

Usage: .venv/bin/python tools/timing_table.py [--only TEXT] [--print]

--only matches the key `rfc check` names a block by, e.g. ``cordic_vectoring (iterative``.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from myhdl import ResetSignal, Signal, always_seq, block, intbv

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the flat wrapper lives under tests/

from rfc.lib.arith import SinCosConfig  # noqa: E402
from rfc.lib.arith.convert_hdl import (  # noqa: E402
    fixed_to_float_pipelined,
    float_to_fixed_pipelined,
)
from rfc.lib.arith.mac_hdl import exact_multiply, fixed_mac, fixed_multiply  # noqa: E402
from rfc.lib.arith.sincos_hdl import sincos  # noqa: E402
from rfc.lib.arith.timing import TABLE, BlockKey, blocks_in, measured_timing  # noqa: E402
from rfc.lib.cordic import CordicConfig  # noqa: E402
from rfc.lib.cordic.hdl import cordic_vectoring  # noqa: E402
from rfc.lib.fixed import FixedFormat  # noqa: E402
from rfc.lib.fixed.hdl import fixed_to_float, float_to_fixed  # noqa: E402
from rfc.toolchain import convert_myhdl, module_estimate, start_new_design  # noqa: E402
from rfc.toolchain.sta import ROUTING_FACTOR  # noqa: E402
from tests.lib.arith.flat import flat_top  # noqa: E402

HANDSHAKE_IN = ("clk", "rst", "in_valid", "in_ready")
HANDSHAKE_OUT = ("out_valid", "out_ready")
#: float64 → fixed formats: the pipelined and iterative quaternion cores', the Franka engine's.
TO_FIXED = (FixedFormat(46, 44), FixedFormat(55, 53), FixedFormat(50, 44))
#: fixed → float64 formats: the two quaternion cores' angles, the Franka engine's words.
TO_FLOAT = (FixedFormat(49, 46), FixedFormat(63, 60), FixedFormat(50, 44))
#: Exact products' operands: the pipelined and the iterative quaternion cores' components, the
#: Franka engine's words (its multiply-accumulate's product).
PRODUCTS = (FixedFormat(46, 44), FixedFormat(55, 53), FixedFormat(50, 44))
#: The pipelined and the iterative quaternion cores' CORDICs.
CORDICS = (
    CordicConfig(width=50, iterations=38, angle_frac=46),
    CordicConfig(width=64, iterations=40, angle_frac=60),
)


def _signed(bits: int) -> Signal:
    return Signal(intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1)))


def _handshake(**data: Signal) -> dict[str, Signal]:
    wires = ("in_valid", "in_ready", "out_valid", "out_ready")
    return {
        "clk": Signal(bool(0)),
        "rst": ResetSignal(0, active=1, isasync=False),
        **{n: Signal(bool(0)) for n in wires},
        **data,
    }


@block
def registered_to_fixed(clk, bits, raw, overflow, invalid, fmt):
    """The combinational float → fixed converter between an input and output registers."""
    held, converted = Signal(intbv(0)[64:]), fmt.signal()
    saturated, nan = Signal(bool(0)), Signal(bool(0))
    convert = float_to_fixed(held, converted, saturated, nan, fmt)

    @always_seq(clk.posedge, reset=None)
    def registers():
        held.next = bits
        raw.next = converted
        overflow.next = saturated
        invalid.next = nan

    return convert, registers


@block
def registered_to_float(clk, raw, bits, fmt):
    """The combinational fixed → float converter between an input and an output register."""
    held, converted = fmt.signal(), Signal(intbv(0)[64:])
    convert = fixed_to_float(held, converted, fmt)

    @always_seq(clk.posedge, reset=None)
    def registers():
        held.next = raw
        bits.next = converted

    return convert, registers


@block
def registered_product(clk, rst, advance, a, b, product):
    """`exact_multiply` with its operand registers (the DSP48s' A and B registers)."""
    held_a, held_b = Signal(a.val), Signal(b.val)
    datapath = exact_multiply(clk, rst, advance, held_a, held_b, product)

    @always_seq(clk.posedge, reset=None)
    def operands():
        if advance:
            held_a.next = a
            held_b.next = b

    return datapath, operands


@dataclass(frozen=True)
class Case:
    """One block at one parameter set: its function, ports in order, further arguments."""

    function: Callable[..., Any]
    order: tuple[str, ...]
    ports: dict[str, Signal]
    extra: tuple[Any, ...]


def cases() -> list[Case]:
    """Every block and parameter set the table holds."""
    found = []
    for fmt in TO_FIXED:
        flags = {"overflow": Signal(bool(0)), "invalid": Signal(bool(0))}
        found.append(
            Case(
                registered_to_fixed,
                ("clk", "bits", "raw", "overflow", "invalid"),
                {"clk": Signal(bool(0)), "bits": Signal(intbv(0)[64:]), "raw": fmt.signal(),
                 **flags},
                (fmt,),
            )
        )  # fmt: skip
        found.append(
            Case(
                float_to_fixed_pipelined,
                (*HANDSHAKE_IN, "bits", *HANDSHAKE_OUT, "raw", "overflow", "invalid"),
                _handshake(bits=Signal(intbv(0)[64:]), raw=fmt.signal(), **flags),
                (fmt,),
            )
        )
    for fmt in TO_FLOAT:
        found.append(
            Case(
                registered_to_float,
                ("clk", "raw", "bits"),
                {"clk": Signal(bool(0)), "raw": fmt.signal(), "bits": Signal(intbv(0)[64:])},
                (fmt,),
            )
        )
        found.append(
            Case(
                fixed_to_float_pipelined,
                (*HANDSHAKE_IN, "raw", *HANDSHAKE_OUT, "bits"),
                _handshake(raw=fmt.signal(), bits=Signal(intbv(0)[64:])),
                (fmt,),
            )
        )
    for fmt in (FixedFormat(18, 16), FixedFormat(50, 44)):
        ports = _handshake(a=fmt.signal(), b=fmt.signal(), product=fmt.signal())
        order = (*HANDSHAKE_IN, "a", "b", *HANDSHAKE_OUT, "product")
        found.append(Case(fixed_multiply, order, ports, (fmt,)))
    fmt = FixedFormat(50, 44)
    ports = _handshake(a=fmt.signal(), b=fmt.signal(), first=Signal(bool(0)), total=fmt.signal())
    order = (*HANDSHAKE_IN, "a", "b", "first", *HANDSHAKE_OUT, "total")
    found.append(Case(fixed_mac, order, ports, (fmt,)))
    for component in PRODUCTS:
        ports = {
            "clk": Signal(bool(0)),
            "rst": ResetSignal(0, active=1, isasync=False),
            "advance": Signal(bool(0)),
            "a": component.signal(),
            "b": component.signal(),
            "product": FixedFormat(2 * component.width, 2 * component.frac_bits).signal(),
        }
        found.append(Case(registered_product, tuple(ports), ports, ()))
    for config in CORDICS:
        for pipelined in (False, True):
            ports = _handshake(
                x=_signed(config.width),
                y=_signed(config.width),
                angle=_signed(config.angle_width),
                magnitude=Signal(intbv(0)[config.magnitude_width :]),
            )
            order = (*HANDSHAKE_IN, "x", "y", *HANDSHAKE_OUT, "angle", "magnitude")
            found.append(Case(cordic_vectoring, order, ports, (config, pipelined)))
    config = SinCosConfig(44)  # the Franka engine's
    for pipelined in (False, True):
        ports = _handshake(
            angle=config.angle_format.signal(),
            cos=config.out_format.signal(),
            sin=config.out_format.signal(),
        )
        order = (*HANDSHAKE_IN, "angle", *HANDSHAKE_OUT, "cos", "sin")
        found.append(Case(sincos, order, ports, (config, pipelined)))
    return found


def elaborate(case: Case) -> tuple[Any, BlockKey]:
    """One case's top-level instance and the key `rfc check` looks its timing up by."""
    start_new_design()
    top = flat_top(case.function, case.order, {}, case.extra)
    instance = top(*(case.ports[n] for n in case.order))
    (key,) = blocks_in(instance)
    return instance, key


def measure(instance: Any, key: BlockKey, work: Path) -> dict[str, Any]:
    """Convert, map and time one case; its row of the table."""
    name = "timed"
    files = convert_myhdl(instance, name, work / f"{len(list(work.iterdir()))}")
    estimate = module_estimate(files[-1], name)
    assert estimate.timing is not None, f"{key} has no timed path"
    resources = estimate.resources
    return {
        "block": key.block,
        "variant": key.variant,
        "parameters": key.parameters,
        "delay_ps": estimate.timing.delay_ps,
        "lut": resources.lut,
        "ff": resources.ff,
        "dsp": resources.dsp,
    }


def markdown(rows: list[dict[str, Any]]) -> str:
    """The table as docs/arithmetic.md shows it."""
    lines = [
        "| block | variant | parameters | LUT | FF | DSP48E1 | cell delay | est. Fmax |",
        "|---|---|---|---:|---:|---:|---:|---:|",
    ]
    for row in rows:
        delay = row["delay_ps"] / 1000
        fmax = 1e3 / (delay * ROUTING_FACTOR)
        lines.append(
            f"| `{row['block']}` | {row['variant']} | {row['parameters']} | {row['lut']:,} | "
            f"{row['ff']:,} | {row['dsp']} | {delay:.2f} ns | {fmax:.0f} MHz |"
        )
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--only",
        help="measure only blocks whose key (as rfc check names it) contains this, "
        "e.g. 'cordic_vectoring (iterative'",
    )
    parser.add_argument("--print", action="store_true", help="print the stored table only")
    args = parser.parse_args()
    if args.print:
        rows = [
            {**vars(t.key), "delay_ps": t.delay_ps, "lut": t.lut, "ff": t.ff, "dsp": t.dsp}
            for t in measured_timing().values()
        ]
        print(markdown(rows))
        return
    stored = json.loads(TABLE.read_text())["blocks"] if TABLE.is_file() else []
    kept = {BlockKey(r["block"], r["variant"], r["parameters"]): r for r in stored}
    with tempfile.TemporaryDirectory(prefix="rfc-timing-table-") as scratch:
        for case in cases():
            instance, key = elaborate(case)
            if args.only and args.only not in str(key):
                continue
            row = measure(instance, key, Path(scratch))
            kept[BlockKey(row["block"], row["variant"], row["parameters"])] = row
            print(markdown([row]).splitlines()[-1], flush=True)
            rows = [kept[key] for key in sorted(kept)]  # kept whole after every block
            TABLE.write_text(json.dumps({"blocks": rows}, indent=1) + "\n", encoding="utf-8")
    print(markdown([kept[key] for key in sorted(kept)]))


if __name__ == "__main__":
    main()
