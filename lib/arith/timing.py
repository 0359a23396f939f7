"""Which rfc.lib blocks a MyHDL design instantiates, and how fast each was measured to be.

A block is known by its name, its variant (combinational, iterative, pipelined) and the
parameters that set its logic (formats, widths, iterations): a `BlockKey`. `blocks_in` walks an
elaborated MyHDL hierarchy and names the known blocks in it; `measured_timing` reads the table
`tools/bench_arith.py --timing-table` writes (`timing.json` beside this module): each key's
7-series cell delay from Yosys' `sta`, with its cells. `rfc check` puts the two together and
warns when a block cannot meet the spec's clock.
"""

from __future__ import annotations

import inspect
import json
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

from rfc.lib.arith import convert_hdl, mac_hdl, sincos_hdl
from rfc.lib.cordic import hdl as cordic_hdl
from rfc.lib.fixed import hdl as fixed_hdl
from rfc.lib.fixed import pipeline as fixed_pipeline
from rfc.lib.fixed.format import FixedFormat

#: The measured table, written by tools/bench_arith.py --timing-table.
TABLE = Path(__file__).with_name("timing.json")

COMBINATIONAL, ITERATIVE, PIPELINED = "combinational", "iterative", "pipelined"


@dataclass(frozen=True, order=True)
class BlockKey:
    """An rfc.lib block at its parameters.

    Attributes:
        block: The block's public name (``cordic_vectoring``, ``float_to_fixed``).
        variant: ``combinational``, ``iterative`` or ``pipelined``.
        parameters: What sets its logic, as the docs write it (``Q2.44``, ``50 bits, 38
            iterations``).
    """

    block: str
    variant: str
    parameters: str

    def __str__(self) -> str:
        return f"{self.block} ({self.variant}, {self.parameters})"


@dataclass(frozen=True)
class BlockTiming:
    """A block's figures, mapped out of context (`synth_xilinx -abc9`), timed by `sta`.

    Attributes:
        key: The block.
        delay_ps: The critical path's cell delay in picoseconds (no routing); a combinational
            block is timed between an input and an output register.
        lut: LUTs.
        ff: Flip-flops.
        dsp: DSP48E1 slices.
    """

    key: BlockKey
    delay_ps: int
    lut: int
    ff: int
    dsp: int


def describe_format(fmt: FixedFormat) -> str:
    """``Q<integer bits>.<fraction bits>``, the sign counted in the integer bits."""
    return f"Q{fmt.int_bits}.{fmt.frac_bits}"


def _cordic(config: Any) -> str:
    return f"{config.width} bits, {config.iterations} iterations, angle Q3.{config.angle_frac}"


def _sincos(config: Any) -> str:
    return f"Q4.{config.frac_bits}, {config.steps} iterations, {config.guard} guard bits"


def _variant(arguments: Mapping[str, Any]) -> str:
    return PIPELINED if arguments.get("pipelined") else ITERATIVE


_Describe = Callable[[Mapping[str, Any]], tuple[str, str, str]]
_FORMAT: Callable[[Mapping[str, Any]], str] = lambda a: describe_format(a["fmt"])  # noqa: E731
#: Each known block function → (name, variant, parameters) from its bound arguments. A
#: datapath and the handshake block around it share a key: the same logic.
_KNOWN: dict[Callable[..., Any], _Describe] = {
    fixed_hdl.float_to_fixed.func: lambda a: ("float_to_fixed", COMBINATIONAL, _FORMAT(a)),
    fixed_hdl.fixed_to_float.func: lambda a: ("fixed_to_float", COMBINATIONAL, _FORMAT(a)),
    fixed_pipeline.float_to_fixed_pipeline.func: lambda a: (
        "float_to_fixed",
        PIPELINED,
        _FORMAT(a),
    ),
    fixed_pipeline.fixed_to_float_pipeline.func: lambda a: (
        "fixed_to_float",
        PIPELINED,
        _FORMAT(a),
    ),
    convert_hdl.float_to_fixed_pipelined.func: lambda a: ("float_to_fixed", PIPELINED, _FORMAT(a)),
    convert_hdl.fixed_to_float_pipelined.func: lambda a: ("fixed_to_float", PIPELINED, _FORMAT(a)),
    cordic_hdl.cordic_vectoring.func: lambda a: (
        "cordic_vectoring",
        _variant(a),
        _cordic(a["config"]),
    ),
    cordic_hdl.cordic_iterative.func: lambda a: (
        "cordic_vectoring",
        ITERATIVE,
        _cordic(a["config"]),
    ),
    cordic_hdl.cordic_pipelined.func: lambda a: (
        "cordic_vectoring",
        PIPELINED,
        _cordic(a["config"]),
    ),
    cordic_hdl.cordic_pipeline.func: lambda a: (
        "cordic_vectoring",
        PIPELINED,
        _cordic(a["config"]),
    ),
    sincos_hdl.sincos.func: lambda a: ("sincos", _variant(a), _sincos(a["config"])),
    sincos_hdl.sincos_iterative.func: lambda a: ("sincos", ITERATIVE, _sincos(a["config"])),
    sincos_hdl.sincos_pipelined.func: lambda a: ("sincos", PIPELINED, _sincos(a["config"])),
    mac_hdl.fixed_multiply.func: lambda a: ("fixed_multiply", PIPELINED, _FORMAT(a)),
    mac_hdl.fixed_mac.func: lambda a: ("fixed_mac", PIPELINED, _FORMAT(a)),
    mac_hdl.mac_pipeline.func: lambda a: ("fixed_mac", PIPELINED, _FORMAT(a)),
    mac_hdl.exact_multiply.func: lambda a: (
        "exact_multiply",
        PIPELINED,
        f"{len(a['a'])} x {len(a['b'])} bits",
    ),
}
#: What to use instead of a block that is too slow, by its name and variant.
SUGGESTIONS: dict[tuple[str, str], str] = {
    ("float_to_fixed", COMBINATIONAL): "rfc.lib.arith.convert_hdl.float_to_fixed_pipelined "
    "(or rfc.lib.fixed.pipeline.float_to_fixed_pipeline inside a pipeline)",
    ("fixed_to_float", COMBINATIONAL): "rfc.lib.arith.convert_hdl.fixed_to_float_pipelined "
    "(or rfc.lib.fixed.pipeline.fixed_to_float_pipeline inside a pipeline)",
    ("cordic_vectoring", ITERATIVE): "cordic_vectoring(..., pipelined=True), or fewer bits",
    ("sincos", ITERATIVE): "sincos(..., pipelined=True), or fewer fraction bits",
    ("fixed_multiply", PIPELINED): "rfc.lib.arith.mac_hdl.exact_multiply (DSP-sized limbs, a "
    "registered adder tree), rounding after it",
    ("fixed_mac", PIPELINED): "exact_multiply products summed in a registered adder tree",
}


def block_key(
    function: Callable[..., Any], args: tuple[Any, ...], kwargs: Mapping[str, Any]
) -> BlockKey | None:
    """The key of a call of a known block function, or None for any other function."""
    describe = _KNOWN.get(function)
    if describe is None:
        return None
    bound = inspect.signature(function).bind(*args, **kwargs)
    bound.apply_defaults()
    return BlockKey(*describe(bound.arguments))


def known_block(block: Any) -> bool:
    """Whether an elaborated MyHDL block instance is a call of a known block function.

    The Verilog holds each such block as a module of its own (`rfc.toolchain.modules`): the
    blocks a core repeats, mapped once by `rfc build --estimate`.
    """
    return block.func in _KNOWN


def blocks_in(instance: Any) -> tuple[BlockKey, ...]:
    """The known blocks of an elaborated MyHDL block instance, each once, in a stable order.

    A known block's own sub-blocks are not listed: its figures include them.
    """
    return tuple(sorted(set(_walk(instance))))


def _walk(instance: Any) -> Iterator[BlockKey]:
    for sub in getattr(instance, "subs", ()):
        if not hasattr(sub, "subs"):  # a process, not a block
            continue
        key = block_key(sub.func, sub.args, sub.kwargs)
        if key is None:
            yield from _walk(sub)
        else:
            yield key


@cache
def measured_timing() -> dict[BlockKey, BlockTiming]:
    """The measured table, by key (empty when it has not been written)."""
    if not TABLE.is_file():
        return {}
    rows = json.loads(TABLE.read_text(encoding="utf-8"))["blocks"]
    table = {}
    for row in rows:
        key = BlockKey(row["block"], row["variant"], row["parameters"])
        table[key] = BlockTiming(key, row["delay_ps"], row["lut"], row["ff"], row["dsp"])
    return table


def suggestion(key: BlockKey) -> str:
    """What to use instead of `key` when it is too slow for the clock."""
    return SUGGESTIONS.get((key.block, key.variant), "a lower clock, or fewer bits")
