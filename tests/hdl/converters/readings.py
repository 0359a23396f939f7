"""Random bags for the converters' three readings, and the loopback run in each reading.

A bag of `SPAN` messages gives every string and byte sequence every length from 0 to 8, so
every length modulo the widest bus (8 bytes) and so modulo every narrower one: each string
or sequence of a message is shorter or longer than the one before by one. Values are random
(seeded); the frames are rosbags' serialization of them. Each reading streams the bag through
the same `rfc msg loopback`: RTL VHDL in GHDL, GHDL's netlist in GHDL, Verilog in Verilator.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from rfc.lib.converters.loopback_run import LoopbackReport, loopback
from rfc.messages.layout import FieldKind, Layout, LayoutField, flatten
from rfc.messages.rosbags_adapter import PRIMITIVE_DTYPES, Middleware, message_types, write_bag
from rfc.messages.values import values_to_message

#: Messages in a bag: lengths 0 … 8 bytes, every length modulo an 8-byte bus.
SPAN = 9
#: The readings: ``rfc msg loopback`` options of each.
READINGS = {
    "rtl": {"simulator": "ghdl"},
    "netlist": {"simulator": "ghdl", "netlist": True},
    "verilog": {"simulator": "verilator"},
}
TOPIC = "/readings"


@dataclass(frozen=True)
class Config:
    """One configuration of the matrix: a type, a middleware, a bus width, a selection."""

    type_name: str
    middleware: Middleware
    width: int
    include: tuple[str, ...] = ()
    exclude: tuple[str, ...] = ()

    @property
    def label(self) -> str:
        selection = [f"+{p}" for p in self.include] + [f"-{p}" for p in self.exclude]
        short = self.type_name.rsplit("/", 1)[-1]
        return "-".join([short, self.middleware.value, str(self.width), *selection])


def random_bag(path: Path, config: Config, seed: int) -> None:
    """Write `SPAN` random messages of the config's type, serialized by rosbags, to `path`."""
    types = message_types(config.middleware)
    canonical = types.resolve(config.type_name)
    layout = flatten(types, canonical)
    rng = np.random.default_rng(seed)
    messages = []
    for index in range(SPAN):
        message = values_to_message(message_values(layout, index, rng), layout, types)
        messages.append((TOPIC, 1000 * (index + 1), types.serialize(message, canonical)))
    write_bag(path, types, {TOPIC: canonical}, messages)


def message_values(layout: Layout, index: int, rng: np.random.Generator) -> dict[str, Any]:
    """Random values of every leaf; the `index`-th message's strings and sequences are of
    length `index` (plus the field's position, modulo `SPAN`)."""
    return {
        leaf.path: _leaf(leaf, (index + position) % SPAN, rng)
        for position, leaf in enumerate(layout.fields)
    }


def _leaf(leaf: LayoutField, length: int, rng: np.random.Generator) -> Any:
    if leaf.bound:
        length = min(length, leaf.bound)
    if leaf.kind is FieldKind.PRIMITIVE:
        return _primitive(leaf.element_type, rng)
    if leaf.kind is FieldKind.STRING:
        return _text(length, rng)
    if leaf.element is not None:  # a sequence of messages: a few, lengths varying within
        return [message_values(leaf.element, length + k, rng) for k in range(length % 3)]
    if leaf.element_type == "string":
        return [_text((length + k) % SPAN, rng) for k in range(length % 4)]
    dtype = PRIMITIVE_DTYPES[leaf.element_type]
    return np.array([_primitive(leaf.element_type, rng) for _ in range(length)], dtype=dtype)


def _primitive(type_name: str, rng: np.random.Generator) -> Any:
    dtype = PRIMITIVE_DTYPES[type_name]
    if dtype.kind == "b":
        return bool(rng.integers(0, 2))
    if dtype.kind == "f":
        return float(dtype.type(rng.normal(scale=1e3)))
    info = np.iinfo(dtype)
    return int(rng.integers(int(info.min), int(info.max), endpoint=True))


def _text(length: int, rng: np.random.Generator) -> str:
    return "".join(chr(c) for c in rng.integers(ord(" "), ord("~"), size=length, endpoint=True))


def run_reading(bag: Path, config: Config, reading: str, workdir: Path) -> LoopbackReport:
    """The bag through `rfc msg loopback`'s converters in one reading."""
    return loopback(
        config.type_name,
        bag,
        width=config.width,
        include=config.include,
        exclude=config.exclude,
        workdir=workdir,
        **READINGS[reading],
    )
