"""The processor's view of a system: where every message goes, derived from the holistic model.

Messages enter from ROS topics (the declared subscribers) and from the logic (PL→PS chunks by
publisher id); they leave to ROS topics (the declared publishers), to the logic (PS→PL chunks by
subscriber id) and to ROS-SW accelerators. A `Route` is one such destination; the plan lists
the routes of every source, using the placement of `rfc.ir.infrastructure`: a subscriber in the
logic sends its messages there once (the logic fans out), a crossing converter carries a
connection between a hardware and a software accelerator.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rfc.ir.model import BlockKind, Connection, Design
from rfc.messages.layout import flatten
from rfc.passes.base import types_of
from rfc.runtime.shaping import Shaper
from rfc.runtime.software import SoftwareAccelerator, load_function

if TYPE_CHECKING:
    from rfc.ir.infrastructure import Converter
    from rfc.messages.rosbags_adapter import MessageTypes


@dataclass(frozen=True)
class ToTopic:
    """Publish on a ROS topic (a declared publisher), shaped as its input port selects."""

    publisher: str
    topic: str
    message: str
    shaper: Shaper


@dataclass(frozen=True)
class ToLogic:
    """Send to the logic as a PS→PL chunk of this subscriber id."""

    subscriber: int
    block: str


@dataclass(frozen=True)
class ToSoftware:
    """Hand to an input of a ROS-SW accelerator, shaped as the connection selects."""

    block: str
    port: int
    port_name: str
    message: str
    shaper: Shaper

    @property
    def name(self) -> str:
        """``Block.port`` as the spec names it."""
        return f"{self.block}.{self.port_name}"


Route = ToTopic | ToLogic | ToSoftware


@dataclass(frozen=True)
class TopicInput:
    """A declared subscriber: the topic it takes and where its messages go."""

    block: str
    topic: str
    message: str
    routes: tuple[Route, ...]


@dataclass(frozen=True)
class TopicOutput:
    """A declared publisher: a topic the system writes."""

    block: str
    topic: str
    message: str


class RuntimePlan:
    """Routes of every message source of a design (stage DERIVED).

    Attributes:
        design: The holistic model.
        types: Its message definitions (for (de)serializing at software accelerators).
        inputs: The declared subscribers, in declaration order.
        outputs: The declared publishers, in declaration order.
        logic_inputs: The subscriber converters in the logic, by id.
        logic_outputs: Where each publisher id's messages go.
        software_outputs: Where each output port of each ROS-SW block sends its messages.
        subscriber_names: Name of each subscriber id (for the account).
        publisher_names: Name of each publisher id.

    Raises:
        RfcError: A ROS-SW accelerator's function cannot be found.
    """

    def __init__(self, design: Design) -> None:
        infrastructure = design.infrastructure
        assert infrastructure is not None, "plan a design at stage DERIVED"
        self.design = design
        self.types: MessageTypes = types_of(design.project)
        self.logic_inputs: tuple[Converter, ...] = infrastructure.subscribers
        self.subscriber_names = {c.id: c.block for c in infrastructure.subscribers}
        self.publisher_names = {c.id: c.block for c in infrastructure.publishers}
        self._software = set(infrastructure.software)
        self._crossing_subscribers = {
            c.crossing.hardware: c for c in infrastructure.subscribers if c.crossing is not None
        }
        self._logic_subscribers = {
            c.block: c for c in infrastructure.subscribers if c.crossing is None
        }
        self.inputs = tuple(
            TopicInput(b.name, b.topic or "", b.message or "", self._subscriber_routes(b.name))
            for b in design.blocks_of(BlockKind.SUBSCRIBER)
        )
        self.outputs = tuple(
            TopicOutput(b.name, b.topic or "", b.message or "")
            for b in design.blocks_of(BlockKind.PUBLISHER)
        )
        self.logic_outputs: dict[int, tuple[Route, ...]] = {
            c.id: self._publisher_routes(c) for c in infrastructure.publishers
        }
        self.software_outputs: dict[str, tuple[tuple[Route, ...], ...]] = {
            name: tuple(self._routes_from(name, port.name) for port in design.block(name).outputs)
            for name in infrastructure.software
        }

    def software_accelerators(self) -> dict[str, SoftwareAccelerator]:
        """Fresh instances of the ROS-SW accelerators (their input slots empty)."""
        accelerators = {}
        for name in self._software:
            block = self.design.block(name)
            kind = self.design.accelerator(block.accelerator or "")
            accelerators[name] = SoftwareAccelerator(block, kind, load_function(kind))
        return accelerators

    @property
    def has_logic(self) -> bool:
        """Whether any part of the system is in the logic."""
        return bool(self.logic_inputs or self.logic_outputs)

    def _subscriber_routes(self, name: str) -> tuple[Route, ...]:
        routes: list[Route] = []
        converter = self._logic_subscribers.get(name)
        if converter is not None:
            routes.append(ToLogic(converter.id, converter.block))
        routes.extend(self._routes_from(name, None, software_only=True))
        return tuple(routes)

    def _publisher_routes(self, converter: Converter) -> tuple[Route, ...]:
        if converter.crossing is None:
            block = self.design.block(converter.block)
            layout = flatten(self.types, converter.message)  # the logic already shaped it
            return (ToTopic(block.name, block.topic or "", converter.message, Shaper(layout)),)
        routes: list[Route] = []
        for target in converter.crossing.software:
            block, _, port = target.partition(".")
            routes.append(self._to_software(block, port))
        return tuple(routes)

    def _routes_from(
        self, block: str, port: str | None, *, software_only: bool = False
    ) -> tuple[Route, ...]:
        return tuple(
            self._route(connection)
            for connection in self.design.connections
            if connection.source.block == block
            and (port is None or connection.source.port == port)
            and (not software_only or connection.destination.block in self._software)
        )

    def _route(self, connection: Connection) -> Route:
        destination = self.design.block(connection.destination.block)
        port = connection.destination.port or ""
        if destination.kind is BlockKind.PUBLISHER:
            layout = destination.port(port).layout
            assert layout is not None
            return ToTopic(
                destination.name, destination.topic or "", layout.type_name, Shaper(layout)
            )
        if destination.name in self._software:
            return self._to_software(destination.name, port)
        converter = self._crossing_subscribers[f"{destination.name}.{port}"]
        return ToLogic(converter.id, converter.block)

    def _to_software(self, block_name: str, port_name: str) -> ToSoftware:
        block = self.design.block(block_name)
        inputs = [p.name for p in block.inputs]
        port = block.port(port_name)
        assert port.layout is not None
        return ToSoftware(
            block_name, inputs.index(port_name), port_name, port.message, Shaper(port.layout)
        )
