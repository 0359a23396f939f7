"""Where each block runs, and the converters the logic needs where data crosses to software.

ROS-SW accelerators run on the processor; every other accelerator is hardware. A subscriber is
in the logic when it feeds a hardware block (an accelerator, or a publisher directly); a
publisher when a hardware block (or a subscriber) feeds it. A connection between a hardware
and a ROS-SW accelerator crosses the DMA: hardware → software needs a publisher converter on
the hardware output (one per output, shared by every software input it feeds), software →
hardware a subscriber converter on the hardware input. Subscribers feeding software and
publishers fed by software need no hardware: the processor takes and sends those messages
itself.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from rfc.ir.fields import with_selection
from rfc.ir.infrastructure import Crossing
from rfc.ir.model import AcceleratorKind, Block, BlockKind, Connection, Design, Endpoint, Port

#: Port names of converters, as the front-ends give them.
CONVERTER_INPUT = "in0"
CONVERTER_OUTPUT = "out0"


@dataclass(frozen=True)
class CrossingConverter:
    """A converter the logic needs at a hardware/software crossing.

    Attributes:
        name: Its derived block name (unique in the design).
        kind: SUBSCRIBER (software → hardware) or PUBLISHER (hardware → software).
        port: The hardware port it serves, with the layout it carries selected.
        crossing: The hardware port and the software ports it joins.
        connections: The original connections it stands for.
    """

    name: str
    kind: BlockKind
    port: Port
    crossing: Crossing
    connections: tuple[Connection, ...]


@dataclass(frozen=True)
class Placement:
    """The split of a design between logic and processor.

    Attributes:
        software: Blocks on the processor (ROS-SW accelerators).
        subscribers: Declared subscribers in the logic, in declaration order.
        publishers: Declared publishers in the logic, in declaration order.
        crossing_subscribers: Subscribers at software → hardware crossings, in connection order.
        crossing_publishers: Publishers at hardware → software crossings, in connection order.
        hardware_connections: Connections inside the logic (see `Infrastructure`).
    """

    software: tuple[str, ...]
    subscribers: tuple[Block, ...]
    publishers: tuple[Block, ...]
    crossing_subscribers: tuple[CrossingConverter, ...]
    crossing_publishers: tuple[CrossingConverter, ...]
    hardware_connections: tuple[Connection, ...]


def software_blocks(design: Design) -> frozenset[str]:
    """Names of the blocks that run on the processor: the ROS-SW accelerators."""
    return frozenset(
        block.name
        for block in design.blocks_of(BlockKind.ACCELERATOR)
        if design.accelerator(block.accelerator or "").kind is AcceleratorKind.ROS_SW
    )


def place(design: Design) -> Placement:
    """Split a flattened design between logic and processor."""
    software = software_blocks(design)
    kinds = {block.name: block.kind for block in design.blocks}

    def hardware(name: str) -> bool:
        return name not in software

    inside = tuple(
        c
        for c in design.connections
        if hardware(c.source.block)
        and hardware(c.destination.block)
        and not (kinds[c.source.block] is BlockKind.SUBSCRIBER and c.destination.block in software)
    )
    fed_from_logic = {c.destination.block for c in inside}
    feeding_logic = {c.source.block for c in inside}
    taken = {block.name.lower() for block in design.blocks}
    crossing_publishers = _crossing_publishers(design, software, kinds, taken)
    crossing_subscribers = _crossing_subscribers(design, software, kinds, taken)
    links = list(inside)
    for converter in crossing_publishers:
        first = converter.connections[0]
        links.append(
            replace(
                first,
                destination=Endpoint(converter.name, CONVERTER_INPUT, first.destination.location),
                fields=tuple(
                    dict.fromkeys(f for c in converter.connections for f in c.fields or ())
                ),
            )
        )
    for converter in crossing_subscribers:
        (only,) = converter.connections
        links.append(
            replace(only, source=Endpoint(converter.name, CONVERTER_OUTPUT, only.source.location))
        )
    return Placement(
        software=tuple(b.name for b in design.blocks if b.name in software),
        subscribers=tuple(
            b for b in design.blocks_of(BlockKind.SUBSCRIBER) if b.name in feeding_logic
        ),
        publishers=tuple(
            b for b in design.blocks_of(BlockKind.PUBLISHER) if b.name in fed_from_logic
        ),
        crossing_subscribers=crossing_subscribers,
        crossing_publishers=crossing_publishers,
        hardware_connections=tuple(links),
    )


def _crosses(
    connection: Connection, software: frozenset[str], kinds: dict[str, BlockKind], to_sw: bool
) -> bool:
    source, destination = connection.source.block, connection.destination.block
    if (
        kinds[source] is not BlockKind.ACCELERATOR
        or kinds[destination] is not BlockKind.ACCELERATOR
    ):
        return False
    if to_sw:
        return source not in software and destination in software
    return source in software and destination not in software


def _unique(name: str, taken: set[str]) -> str:
    candidate, number = name, 2
    while candidate.lower() in taken:
        candidate, number = f"{name}{number}", number + 1
    taken.add(candidate.lower())
    return candidate


def _crossing_publishers(
    design: Design, software: frozenset[str], kinds: dict[str, BlockKind], taken: set[str]
) -> tuple[CrossingConverter, ...]:
    by_output: dict[tuple[str, str], list[Connection]] = {}
    for connection in design.connections:
        if _crosses(connection, software, kinds, to_sw=True):
            key = (connection.source.block, connection.source.port or "")
            by_output.setdefault(key, []).append(connection)
    converters = []
    for (block, port_name), connections in by_output.items():
        port = design.block(block).port(port_name)
        assert port.layout is not None
        carried = frozenset(f for c in connections for f in c.fields or ())
        converters.append(
            CrossingConverter(
                name=_unique(f"{block}_{port_name}_pub", taken),
                kind=BlockKind.PUBLISHER,
                port=replace(port, layout=with_selection(port.layout, carried)),
                crossing=Crossing(
                    f"{block}.{port_name}", tuple(str(c.destination) for c in connections)
                ),
                connections=tuple(connections),
            )
        )
    return tuple(converters)


def _crossing_subscribers(
    design: Design, software: frozenset[str], kinds: dict[str, BlockKind], taken: set[str]
) -> tuple[CrossingConverter, ...]:
    converters = []
    for connection in design.connections:
        if not _crosses(connection, software, kinds, to_sw=False):
            continue
        block, port_name = connection.destination.block, connection.destination.port or ""
        converters.append(
            CrossingConverter(
                name=_unique(f"{block}_{port_name}_sub", taken),
                kind=BlockKind.SUBSCRIBER,
                port=design.block(block).port(port_name),
                crossing=Crossing(f"{block}.{port_name}", (str(connection.source),)),
                connections=(connection,),
            )
        )
    return tuple(converters)
