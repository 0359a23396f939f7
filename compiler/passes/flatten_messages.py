"""flatten-messages: every block port gets its message layout, selected as it is used.

An input port uses the fields its one connection carries; an output port the union of what
its connections carry (a subscriber parses every field but presents only these; an accelerator
output left unconnected selects nothing). Ports of the accelerator types stay unflattened:
different instances of one type may be connected differently.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.ir.model import Block, Design, Direction, Port, Stage
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.passes.base import types_of
from rfc.passes.selections import layout_selecting


@dataclass(frozen=True)
class FlattenMessages:
    """Attach the selected layout of its message to every block port."""

    name: ClassVar[str] = "flatten-messages"

    def apply(self, design: Design) -> Design:
        """Return the design at stage FLATTENED."""
        types = types_of(design.project)
        used: dict[tuple[str, str, Direction], set[str]] = defaultdict(set)
        for connection in design.connections:
            fields = set(connection.fields or ())
            source, destination = connection.source, connection.destination
            assert source.port is not None
            assert destination.port is not None
            used[(source.block, source.port, Direction.OUT)] |= fields
            used[(destination.block, destination.port, Direction.IN)] |= fields
        blocks = tuple(_flatten_block(types, block, used) for block in design.blocks)
        return replace(design, blocks=blocks, stage=Stage.FLATTENED)


def _flatten_block(
    types: MessageTypes, block: Block, used: dict[tuple[str, str, Direction], set[str]]
) -> Block:
    return replace(block, ports=tuple(_flatten_port(types, block, p, used) for p in block.ports))


def _flatten_port(
    types: MessageTypes, block: Block, port: Port, used: dict[tuple[str, str, Direction], set[str]]
) -> Port:
    paths = frozenset(used.get((block.name, port.name, port.direction), ()))
    return replace(port, layout=layout_selecting(types, port.message, paths))
