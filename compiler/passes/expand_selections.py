"""expand-selections: include/exclude hints become explicit field lists.

This is the paper's *extended system specification* (§5.1): the concise hints of the spec are
expanded, by analysing the message definition, into every leaf field a connection carries.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.ir.model import Connection, Design, Stage
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
        connections = tuple(_expand(types, c) for c in design.connections)
        return replace(design, connections=connections, stage=Stage.EXPANDED)


def _expand(types: MessageTypes, connection: Connection) -> Connection:
    assert connection.message is not None
    fields = carried_fields(types, connection.message, connection.include, connection.exclude)
    return replace(connection, fields=fields)
