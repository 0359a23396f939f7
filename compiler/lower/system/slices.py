"""Registered boundaries: a register slice on each message handed from one block to another.

Between a converter and an accelerator the top level puts `rfc.lib.slice` on the message's
fields and valid/ready, so that everything one block hands the next comes from a flip-flop and
no combinational path crosses from one block into another. A message with strings or
sequences (sub-streams with handshakes of their own) is wired directly, as before.
"""

from __future__ import annotations

from pathlib import Path

from rfc.lower.netlist import Mode
from rfc.lower.system.components import Component, slice_component
from rfc.lower.system.interfaces import MESSAGE
from rfc.lower.system.top import Interface, Terminal, TopBuilder

_VALID, _READY = f"{MESSAGE}_valid", f"{MESSAGE}_ready"
#: Names that belong to a handshake of their own (a sub-stream's), not to the message's fields.
_HANDSHAKE_ENDINGS = ("_valid", "_ready", "_last")


class RegisterSlices:
    """The slices of a system and the components (one per message shape) they need.

    Args:
        prefix: The project's identifier, which the slice entities' names start with.
        directory: Where the VHDL goes.
    """

    def __init__(self, prefix: str, directory: Path) -> None:
        self.prefix, self.directory = prefix, directory
        self.components: list[Component] = []
        self._by_shape: dict[tuple[tuple[str, int, bool], ...], Component] = {}

    def insert(self, builder: TopBuilder, target: Interface, label: str) -> Interface:
        """Put a slice labelled `label` in front of `target`, wired to it.

        Returns:
            The slice's input side, to wire the producer to; `target` itself when the message
            has sub-streams, which are not sliced.
        """
        if not _sliceable(builder, target):
            return target
        fields = tuple(
            (name, builder.port(t).bits, builder.port(t).wire)
            for name, t in target.items()
            if name not in (_VALID, _READY)
        )
        component = self._by_shape.get(fields)
        if component is None:
            name = f"{self.prefix}_slice{len(self._by_shape)}"
            component = slice_component(fields, self.directory, name)
            self._by_shape[fields] = component
            self.components.append(component)
        builder.cell(label, component.entity)
        for name, _, _ in fields:
            builder.wire(Terminal(label, f"m_{name}"), target[name])
        builder.wire(Terminal(label, "m_valid"), target[_VALID])
        builder.wire(target[_READY], Terminal(label, "m_ready"))
        inputs = {name: Terminal(label, f"s_{name}") for name, _, _ in fields}
        return {**inputs, _VALID: Terminal(label, "s_valid"), _READY: Terminal(label, "s_ready")}


def _sliceable(builder: TopBuilder, target: Interface) -> bool:
    """A message of fields and one handshake, every field an input of the consumer."""
    if _VALID not in target or _READY not in target:
        return False
    others = [n for n in target if n not in (_VALID, _READY)]
    if any(n.endswith(_HANDSHAKE_ENDINGS) for n in others):
        return False
    return all(builder.port(target[n]).mode is Mode.IN for n in others)
