"""check-connections: every connection joins two real ports of one message type, soundly.

Checks, in order: the project has blocks; names are valid and unique; each connection's
blocks and ports exist (ports are inferred when unambiguous); message types agree; include and
exclude patterns name real fields, select something, and cover what the destination needs; no
input is fed twice; the graph has no cycle, every block is reached from a subscriber and leads
to a publisher; every input is fed. Fan-out (one output to many inputs) is allowed.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.errors import RfcError, did_you_mean
from rfc.ir.model import Block, BlockKind, Connection, Design, Direction, Endpoint, Port, Stage
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.messages.selection import validate_pattern
from rfc.passes.base import types_of
from rfc.passes.generated_names import check_generated_names
from rfc.passes.graph import check_graph
from rfc.passes.names import check_identifier, check_topic, check_unique
from rfc.passes.selections import carried_fields


@dataclass(frozen=True)
class CheckConnections:
    """Resolve connection endpoints and check the data-flow graph."""

    name: ClassVar[str] = "check-connections"

    def apply(self, design: Design) -> Design:
        """Return the design at stage CONNECTED: every endpoint names its port."""
        if not design.blocks:
            raise RfcError(
                f"project '{design.project.name}' has no blocks",
                location=design.project.location,
                hint="a system needs at least a subscriber, an accelerator and a publisher",
            )
        _check_names(design)
        types = types_of(design.project)
        _check_port_needs(design, types)
        blocks = {block.name: block for block in design.blocks}
        connections = tuple(_resolve(connection, blocks) for connection in design.connections)
        for connection in connections:
            _check_selection(connection, blocks, types)
        _check_fed_once(connections)
        check_graph(design.blocks, connections)
        _check_all_fed(design.blocks, connections)
        return replace(design, connections=connections, stage=Stage.CONNECTED)


def _check_names(design: Design) -> None:
    project = design.project
    check_identifier(project.name, "project name", project.at("name"))
    for accelerator in design.accelerators:
        check_identifier(accelerator.name, "accelerator type", accelerator.at("name"))
        for port in accelerator.ports:
            check_identifier(
                port.name, "port", port.at("name"), f" of accelerator '{accelerator.name}'"
            )
        check_unique(
            ((p.name, p.at("name")) for p in accelerator.ports),
            "port",
            f" in accelerator '{accelerator.name}'",
        )
    for block in design.blocks:
        check_identifier(block.name, "block", block.at("name"))
        if block.topic is not None:
            check_topic(block.topic, f"{block.kind.value} '{block.name}'", block.at("topic"))
    check_unique(((b.name, b.at("name")) for b in design.blocks), "block")
    check_generated_names(design)


def _check_port_needs(design: Design, types: MessageTypes) -> None:
    for accelerator in design.accelerators:
        for port in accelerator.ports:
            if port.needs and port.direction is Direction.OUT:
                raise RfcError(
                    f"output '{port.name}' of accelerator '{accelerator.name}' has include or "
                    "exclude; only inputs say which fields they need (connections select what "
                    "an output sends)",
                    location=port.at("include" if port.needs.include else "exclude"),
                )
            layout = flatten(types, port.message)
            for key, pattern in port.needs.patterns():
                validate_pattern(layout, pattern, port.at(key))


def _resolve(connection: Connection, blocks: dict[str, Block]) -> Connection:
    source = _block(connection.source, connection, blocks)
    destination = _block(connection.destination, connection, blocks)
    what = f"connection from '{source.name}' to '{destination.name}'"
    if source.kind is BlockKind.PUBLISHER:
        raise RfcError(
            f"publisher '{source.name}' sends to '{destination.name}', but a publisher's "
            "messages go to ROS",
            location=connection.location,
            hint="connect the block that feeds the publisher instead",
        )
    if destination.kind is BlockKind.SUBSCRIBER:
        raise RfcError(
            f"block '{source.name}' sends to subscriber '{destination.name}', but a subscriber "
            "receives only from ROS",
            location=connection.destination.location,
        )
    outputs = _named(source, source.outputs, connection.source, "output")
    inputs = _named(destination, destination.inputs, connection.destination, "input")
    if len(outputs) == 1 and len(inputs) == 1:
        pairs = [(outputs[0], inputs[0])]
    else:
        pairs = [(o, i) for o in outputs for i in inputs if o.message == i.message]
    if not pairs:
        raise RfcError(
            f"type mismatch: '{source.name}' sends {_typed(outputs)}, but "
            f"'{destination.name}' takes {_typed(inputs)}",
            location=connection.location,
        )
    if len(pairs) > 1:
        options = " or ".join(f"{o.name} → {i.name}" for o, i in pairs)
        raise RfcError(
            f"{what} is ambiguous: it could join {options}",
            location=connection.location,
            hint="name the ports: 'from:' and 'port:' in YAML, block['port'] in Python",
        )
    output, input_ = pairs[0]
    if output.message != input_.message:
        raise RfcError(
            f"type mismatch: '{source.name}.{output.name}' sends {output.message}, but "
            f"'{destination.name}.{input_.name}' takes {input_.message}",
            location=connection.location,
        )
    return replace(
        connection,
        source=replace(connection.source, port=output.name),
        destination=replace(connection.destination, port=input_.name),
        message=output.message,
    )


def _typed(ports: list[Port]) -> str:
    return ", ".join(f"{p.message} ({p.name})" for p in ports)


def _block(endpoint: Endpoint, connection: Connection, blocks: dict[str, Block]) -> Block:
    block = blocks.get(endpoint.block)
    if block is not None:
        return block
    other = connection.source if endpoint is connection.destination else connection.destination
    raise RfcError(
        f"block '{other.block}' is connected to '{endpoint.block}', which is not a block",
        location=endpoint.location,
        hint=did_you_mean(endpoint.block, blocks) or f"the blocks are {', '.join(blocks)}",
    )


def _named(block: Block, ports: tuple[Port, ...], endpoint: Endpoint, what: str) -> list[Port]:
    if not ports:
        raise RfcError(
            f"{block.kind.value} '{block.name}' has no {what}", location=endpoint.location
        )
    if endpoint.port is None:
        return list(ports)
    for port in ports:
        if port.name == endpoint.port:
            return [port]
    names = [p.name for p in ports]
    raise RfcError(
        f"block '{block.name}' has no {what} '{endpoint.port}'; its {what}s are {', '.join(names)}",
        location=endpoint.location,
        hint=did_you_mean(endpoint.port, names),
    )


def _check_selection(connection: Connection, blocks: dict[str, Block], types: MessageTypes) -> None:
    assert connection.message is not None
    assert connection.destination.port is not None
    layout = flatten(types, connection.message)
    for key, pattern in connection.carries.patterns():
        validate_pattern(layout, pattern, connection.at(key))
    carried = set(carried_fields(types, connection.message, connection.carries))
    what = f"connection from '{connection.source.block}' to '{connection.destination}'"
    if not carried:
        raise RfcError(
            f"{what} carries no field: its include and exclude leave nothing",
            location=connection.location,
        )
    port = blocks[connection.destination.block].port(connection.destination.port)
    if port.needs:
        needed = carried_fields(types, connection.message, port.needs)
        missing = [path for path in needed if path not in carried]
        if missing:
            more = f" (and {len(missing) - 1} more)" if len(missing) > 1 else ""
            raise RfcError(
                f"{what} does not carry '{missing[0]}'{more}, which input '{port.name}' of "
                f"'{connection.destination.block}' needs",
                location=connection.location,
                hint=f"include it, or drop it from the needs of input '{port.name}' "
                f"(at {port.location})",
            )


def _check_fed_once(connections: tuple[Connection, ...]) -> None:
    feeding: dict[tuple[str, str | None], Connection] = {}
    for connection in connections:
        key = (connection.destination.block, connection.destination.port)
        if key in feeding:
            first = feeding[key]
            raise RfcError(
                f"input '{connection.destination.port}' of block "
                f"'{connection.destination.block}' is fed twice: from "
                f"'{first.source.block}' (at {first.location}) and from "
                f"'{connection.source.block}'",
                location=connection.location,
                hint="an input takes one connection; add an input port to merge streams",
            )
        feeding[key] = connection


def _check_all_fed(blocks: tuple[Block, ...], connections: tuple[Connection, ...]) -> None:
    fed = {(c.destination.block, c.destination.port) for c in connections}
    for block in blocks:
        for port in block.inputs:
            if (block.name, port.name) not in fed:
                raise RfcError(
                    f"input '{port.name}' of block '{block.name}' is not fed by any connection",
                    location=block.location,
                    hint=f"connect a {port.message} output to it",
                )
