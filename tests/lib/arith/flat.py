"""Blocks whose ports are lists of signals, wrapped in a top level with one port per signal.

MyHDL converts only top levels with named scalar ports, so the wrapper's source is written out
with a parameter per signal (``<group><index>``) and handed to the inner block as lists.
"""

from __future__ import annotations

import linecache
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from myhdl import Signal, block


def flat_top(
    inner: Callable[..., Any],
    order: Sequence[str],
    groups: Mapping[str, int],
    extra: Sequence[Any] = (),
) -> Callable[..., Any]:
    """A ``@block`` taking ``order``'s ports flat (lists expanded) and calling `inner`.

    Args:
        inner: The block; called with the ports in `order`, lists for names in `groups`, then
            `extra`.
        order: Port names in `inner`'s order.
        groups: Names that are lists, with their lengths.
        extra: Further (non-signal) arguments of `inner`.
    """
    params = [
        f"{name}{i}" if name in groups else name
        for name in order
        for i in range(groups.get(name, 1))
    ]
    calls = [
        "[" + ", ".join(f"{name}{i}" for i in range(groups[name])) + "]" if name in groups else name
        for name in order
    ]
    source = f"def top({', '.join(params)}):\n    return inner({', '.join(calls)}, *extra)\n"
    # MyHDL reads a block's source: keep it where `inspect` looks for it.
    filename = f"<flat_top {inner.__name__} {len(params)}>"
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    namespace: dict[str, Any] = {"inner": inner, "extra": tuple(extra)}
    exec(compile(source, filename, "exec"), namespace)
    return block(namespace["top"])


def flat_ports(ports: Mapping[str, Signal | list[Signal]]) -> dict[str, Signal]:
    """The flat name → signal map matching `flat_top`'s parameters."""
    flat: dict[str, Signal] = {}
    for name, value in ports.items():
        if isinstance(value, list):
            flat.update({f"{name}{i}": signal for i, signal in enumerate(value)})
        else:
            flat[name] = value
    return flat
