"""expand-selections: include/exclude hints become explicit field lists.

This is the paper's *extended system specification* (§5.1): the concise hints of the spec are
expanded, by analysing the message definition, into every leaf field a connection carries.
A connection into an accelerator input that names its needs (``rfc.port(..., include=...)``)
carries just those: the subscriber parses the rest and drops it.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.ir.model import Connection, Design, Port, Stage
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.passes.base import types_of
from rfc.passes.selections import carried_fields


@dataclass(frozen=True)
class ExpandSelections:
    """List every leaf field each connection carries, in serialization order."""

    name: ClassVar[str] = "expand-selections"

    def apply(self, design: Design) -> Design:
        """Return the design at stage EXPANDED."""
        types = types_of(design.project)
        ports = {(b.name, p.name): p for b in design.blocks for p in b.inputs}
        connections = tuple(_expand(types, c, ports) for c in design.connections)
        return replace(design, connections=connections, stage=Stage.EXPANDED)


def _expand(
    types: MessageTypes, connection: Connection, inputs: dict[tuple[str, str], Port]
) -> Connection:
    assert connection.message is not None
    fields = carried_fields(types, connection.message, connection.carries)
    port = inputs.get((connection.destination.block, connection.destination.port or ""))
    if port is not None and port.needs:
        needed = set(carried_fields(types, connection.message, port.needs))
        fields = tuple(path for path in fields if path in needed)
    return replace(connection, fields=fields)
