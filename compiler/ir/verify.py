"""The invariants of the IR at each stage; the pipeline checks them after every pass.

A failed invariant is a bug in rfc (a pass produced an inconsistent design), not an error in
the user's spec, so it raises `IrInvariantError` rather than `RfcError`.
"""

from __future__ import annotations

from collections import Counter

from rfc.errors import SourceLocation
from rfc.ir.fields import selected_paths
from rfc.ir.model import BlockKind, Design, Direction, Port, Stage


class IrInvariantError(RuntimeError):
    """A design breaks an invariant of its stage: a pass is wrong."""


def _require(condition: bool, message: str) -> None:
    if not condition:
        raise IrInvariantError(message)


def verify(design: Design) -> None:
    """Check every invariant of `design.stage` and of the stages before it.

    Raises:
        IrInvariantError: An invariant does not hold; the message names it.
    """
    _verify_parsed(design)
    checks = (
        (Stage.TYPED, _verify_typed),
        (Stage.CONNECTED, _verify_connected),
        (Stage.EXPANDED, _verify_expanded),
        (Stage.FLATTENED, _verify_flattened),
        (Stage.DERIVED, _verify_derived),
    )
    for stage, check in checks:
        if design.stage >= stage:
            check(design)


def _verify_parsed(design: Design) -> None:
    nodes: list[object] = [design.project, *design.accelerators, *design.blocks]
    nodes += [p for t in design.accelerators for p in t.ports]
    nodes += [p for b in design.blocks for p in b.ports]
    nodes += design.connections
    for node in nodes:
        if not isinstance(getattr(node, "location", None), SourceLocation):
            raise IrInvariantError(f"{node!r} has no source location")
    for accelerator in design.accelerators:
        _require(
            all(p.direction is Direction.IN for p in accelerator.inputs)
            and all(p.direction is Direction.OUT for p in accelerator.outputs),
            f"ports of {accelerator.name} are filed under the wrong direction",
        )
    for block in design.blocks:
        converter = block.kind is not BlockKind.ACCELERATOR
        _require(
            converter == (block.message is not None) and converter != bool(block.accelerator),
            f"block {block.name} mixes converter and accelerator attributes",
        )


def _canonical(message: str) -> bool:
    return message.count("/") == 2 and "/msg/" in message


def _verify_typed(design: Design) -> None:
    names = Counter(t.name for t in design.accelerators)
    _require(all(n == 1 for n in names.values()), "accelerator type names are not unique")
    for block in design.blocks:
        _require(
            all(_canonical(p.message) for p in block.ports),
            f"block {block.name} has a port of unresolved type",
        )
        if block.kind is BlockKind.ACCELERATOR:
            expected = design.accelerator(block.accelerator or "").ports
            _require(
                tuple(p.name for p in block.ports) == tuple(p.name for p in expected),
                f"block {block.name} lost the ports of its type",
            )
        else:
            want = Direction.OUT if block.kind is BlockKind.SUBSCRIBER else Direction.IN
            _require(
                len(block.ports) == 1
                and block.ports[0].direction is want
                and block.ports[0].message == block.message,
                f"converter {block.name} needs one {want.value} port of its message",
            )


def _port(design: Design, block: str, name: str | None) -> Port:
    _require(name is not None, f"connection endpoint {block} has no port")
    return design.block(block).port(name or "")


def _verify_connected(design: Design) -> None:
    names = Counter(b.name.lower() for b in design.blocks)
    _require(all(n == 1 for n in names.values()), "block names are not unique")
    fed: Counter[tuple[str, str | None]] = Counter()
    for connection in design.connections:
        source = _port(design, connection.source.block, connection.source.port)
        destination = _port(design, connection.destination.block, connection.destination.port)
        _require(
            source.direction is Direction.OUT and destination.direction is Direction.IN,
            f"connection {connection.source} → {connection.destination} runs backwards",
        )
        _require(
            source.message == destination.message == connection.message,
            f"connection {connection.source} → {connection.destination} mixes types",
        )
        fed[(connection.destination.block, connection.destination.port)] += 1
    for block in design.blocks:
        for port in block.inputs:
            _require(
                fed[(block.name, port.name)] == 1,
                f"input {block.name}.{port.name} is fed {fed[(block.name, port.name)]} times",
            )


def _verify_expanded(design: Design) -> None:
    for connection in design.connections:
        _require(
            bool(connection.fields),
            f"connection {connection.source} → {connection.destination} lists no fields",
        )


def _verify_flattened(design: Design) -> None:
    incoming = {(c.destination.block, c.destination.port): c for c in design.connections}
    for block in design.blocks:
        for port in block.ports:
            _require(
                port.layout is not None and port.layout.type_name == port.message,
                f"port {block.name}.{port.name} has no layout of its message",
            )
            if port.direction is Direction.IN and port.layout is not None:
                connection = incoming[(block.name, port.name)]
                _require(
                    tuple(selected_paths(port.layout)) == connection.fields,
                    f"input {block.name}.{port.name} selects other fields than it is fed",
                )


def _verify_derived(design: Design) -> None:
    infrastructure = design.infrastructure
    _require(infrastructure is not None, "a derived design has no infrastructure")
    assert infrastructure is not None
    software = set(infrastructure.software)
    for kind, converters in (
        (BlockKind.SUBSCRIBER, infrastructure.subscribers),
        (BlockKind.PUBLISHER, infrastructure.publishers),
    ):
        declared = [c.block for c in converters if c.crossing is None]
        _require(
            [c.id for c in converters] == list(range(len(converters)))
            and [c.block for c in converters[: len(declared)]] == declared
            and all(design.block(name).kind is kind for name in declared)
            and declared == sorted(declared, key=[b.name for b in design.blocks].index),
            f"{kind.value} ids are not 0..n-1, declared converters first in declaration order",
        )
        _require(
            not any(name in software for name in declared),
            f"a {kind.value} in the logic is also on the processor",
        )
    inputs = infrastructure.scheduler.inputs
    _require(
        [(i.index, i.publisher) for i in inputs]
        == [(c.id, c.block) for c in infrastructure.publishers],
        "the scheduler needs exactly one input per publisher, indexed by its id",
    )
    for converter in infrastructure.publishers:
        _require(
            converter.needs_frame_length == (converter.frame_bytes is None),
            f"publisher {converter.block}: a frame-length circuit iff its size is unknown",
        )
