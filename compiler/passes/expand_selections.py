"""expand-selections: include/exclude hints become explicit field lists.

This is the paper's *extended system specification* (§5.1): the concise hints of the spec are
expanded, by analysing the message definition, into every leaf field a connection carries.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.ir.fields import selected_paths
from rfc.ir.model import Connection, Design, Stage
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.messages.selection import select
from rfc.passes.base import types_of


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
    layout = select(flatten(types, connection.message), connection.include, connection.exclude)
    return replace(connection, fields=tuple(selected_paths(layout)))
