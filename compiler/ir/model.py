"""The typed data-flow graph every pass reads and returns: the spec as rfc understands it.

The graph has accelerator *types* (what a kind of accelerator is: sources and typed ports),
*blocks* (the components of the system: subscriber converters, accelerator instances, publisher
converters) and *connections* (a source port to a destination port, carrying a field
selection). Every node records where the user wrote it (`SourceLocation`), so that a pass can
point at the offending spec element.

All nodes are frozen: a pass returns a new `Design` (`dataclasses.replace`). The `stage` says
how far the pipeline has got, and `rfc.ir.verify` checks the invariants of that stage.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from enum import IntEnum, StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rfc.errors import SourceLocation

# Which way data flows through a port: the converters' own direction, one enum for every layer.
from rfc.lib.converters.ports import Direction as Direction
from rfc.messages.limits import Limits

if TYPE_CHECKING:
    from rfc.ir.infrastructure import Infrastructure
    from rfc.messages.layout import Layout
    from rfc.messages.rosbags_adapter import Middleware

#: Scheduling algorithms of the PL→PS scheduler (docs/schedulers.md); ``auto`` is left to the DSE.
SCHEDULER_ALGORITHMS = ("LRU", "NPFP", "PFP", "ROEDF", "LOEDF", "LST", "auto")


class _Spotted:
    """Nodes that remember where each of their attributes was written."""

    location: SourceLocation
    spots: Mapping[str, SourceLocation]

    def at(self, attribute: str) -> SourceLocation:
        """Return where an attribute was written, or the node's own location."""
        return self.spots.get(attribute, self.location)


class Stage(IntEnum):
    """How far a design has been through the pipeline; each pass moves it one stage on."""

    PARSED = 0
    """Straight from a front-end: names and message types as the user wrote them."""
    TYPED = 1
    """Message types canonical, every block has its typed ports."""
    CONNECTED = 2
    """Every connection joins two existing ports of the same message type; graph checked."""
    EXPANDED = 3
    """Every connection lists the leaf fields it carries."""
    FLATTENED = 4
    """Every block port holds its message layout with the fields it uses selected."""
    DERIVED = 5
    """The infrastructure (ids, DMA, frame-length circuits, scheduler inputs) is derived."""
    CHECKED = 6
    """The logic's rules hold: names, accelerator sources, fan-out, block RAM."""


class BlockKind(StrEnum):
    """What a block is in the system."""

    SUBSCRIBER = "subscriber"
    """ROS>accelerator: receives a topic from the processor and presents its fields."""
    PUBLISHER = "publisher"
    """accelerator>ROS: serializes fields into a message sent to the processor."""
    ACCELERATOR = "accelerator"
    """An instance of one of the accelerator types."""


class AcceleratorKind(StrEnum):
    """How an accelerator is implemented."""

    HLS = "HLS"
    VHDL = "VHDL"
    MYHDL = "MyHDL"
    ROS_SW = "ROS-SW"


@dataclass(frozen=True)
class FieldSelection:
    """Which fields of a message: what an accelerator input needs, what a connection carries.

    Patterns are dotted field paths with ``*`` wildcards. The node holding a selection keeps
    where each pattern was written in its ``spots``, under the keys `patterns` yields.

    Attributes:
        include: The fields selected; empty means every field.
        exclude: The fields left out.
    """

    include: tuple[str, ...] = ()
    exclude: tuple[str, ...] = ()

    def __bool__(self) -> bool:
        """False when it has no pattern, that is when it selects the whole message."""
        return bool(self.include or self.exclude)

    def __add__(self, other: FieldSelection) -> FieldSelection:
        """The patterns of both: what ``a.include(...) >> b.exclude(...)`` carries."""
        return FieldSelection(self.include + other.include, self.exclude + other.exclude)

    def patterns(self) -> Iterator[tuple[str, str]]:
        """Each pattern with its spot key (``include[0]``, ``exclude[1]``, ...)."""
        for key, patterns in (("include", self.include), ("exclude", self.exclude)):
            for index, pattern in enumerate(patterns):
                yield f"{key}[{index}]", pattern


@dataclass(frozen=True)
class Port(_Spotted):
    """A typed port of an accelerator type or a block.

    Attributes:
        name: Port name, unique within its owner.
        direction: Whether the owner receives (IN) or sends (OUT) messages through it.
        message: Message type: as written until resolve-types, canonical (``pkg/msg/Name``)
            after.
        location: Where the port (or the block that implies it) was written.
        needs: For an accelerator input: the fields it needs (empty: all).
        layout: From flatten-messages on: the message layout with the fields that flow through
            this port selected.
        spots: Locations of individual attributes (``message``, ``include[0]``, ...).
    """

    name: str
    direction: Direction
    message: str
    location: SourceLocation
    needs: FieldSelection = FieldSelection()
    layout: Layout | None = None
    spots: Mapping[str, SourceLocation] = field(default_factory=dict, compare=False, repr=False)


@dataclass(frozen=True)
class FunctionRef:
    """A Python function named by the spec: the file that defines it and its name."""

    file: Path
    name: str


@dataclass(frozen=True)
class AcceleratorType(_Spotted):
    """A kind of accelerator: how it is implemented and which messages it takes and gives.

    Attributes:
        name: Type name, referred to by blocks' ``type``.
        kind: HLS, VHDL, MyHDL or ROS-SW.
        sources: Absolute paths of its source files (checked to exist by the front-end).
        inputs: Input ports in declaration order.
        outputs: Output ports in declaration order.
        location: Where the type was defined.
        top: MyHDL: the name of the ``@block`` function; others: the top-level entity or
            function when given, else None.
        reference: The Python reference model, when one is named.
        block_function: Python specs: the MyHDL block function itself.
        reference_function: Python specs: the reference callable itself.
        spots: Locations of individual attributes.
    """

    name: str
    kind: AcceleratorKind
    sources: tuple[Path, ...]
    inputs: tuple[Port, ...]
    outputs: tuple[Port, ...]
    location: SourceLocation
    top: str | None = None
    reference: FunctionRef | None = None
    block_function: Callable[..., Any] | None = field(default=None, compare=False, repr=False)
    reference_function: Callable[..., Any] | None = field(default=None, compare=False, repr=False)
    spots: Mapping[str, SourceLocation] = field(default_factory=dict, compare=False, repr=False)

    @property
    def ports(self) -> tuple[Port, ...]:
        """Inputs, then outputs."""
        return self.inputs + self.outputs


@dataclass(frozen=True)
class Block(_Spotted):
    """A component of the system.

    Attributes:
        name: Block name, unique in the design.
        kind: Subscriber, publisher or accelerator.
        location: Where the block was written.
        message: Converters: the message type (as written, canonical after resolve-types).
        topic: Converters: the ROS topic.
        accelerator: Accelerators: the name of their type.
        period: Clock cycles between messages, when given.
        deadline: Clock cycles from a message's arrival to its completion, when given.
        max_bytes: Largest frame the converter accepts, when given.
        ports: From resolve-types on: the block's typed ports.
        spots: Locations of individual attributes.
    """

    name: str
    kind: BlockKind
    location: SourceLocation
    message: str | None = None
    topic: str | None = None
    accelerator: str | None = None
    period: int | None = None
    deadline: int | None = None
    max_bytes: int | None = None
    ports: tuple[Port, ...] = ()
    spots: Mapping[str, SourceLocation] = field(default_factory=dict, compare=False, repr=False)

    def port(self, name: str) -> Port:
        """Return the port with this name."""
        for candidate in self.ports:
            if candidate.name == name:
                return candidate
        raise KeyError(name)

    @property
    def inputs(self) -> tuple[Port, ...]:
        """Ports that receive messages."""
        return tuple(p for p in self.ports if p.direction is Direction.IN)

    @property
    def outputs(self) -> tuple[Port, ...]:
        """Ports that send messages."""
        return tuple(p for p in self.ports if p.direction is Direction.OUT)


@dataclass(frozen=True)
class Endpoint:
    """One end of a connection: a block and, once known, its port."""

    block: str
    port: str | None
    location: SourceLocation

    def __str__(self) -> str:
        return self.block if self.port is None else f"{self.block}.{self.port}"


@dataclass(frozen=True)
class Connection(_Spotted):
    """Messages flowing from a source port to a destination port.

    Attributes:
        source: The sending block (and port, inferred by check-connections when not given).
        destination: The receiving block (and port).
        location: Where the connection was written (an ``outgoing`` entry, a ``>>``).
        carries: The fields it carries (empty: all).
        message: From check-connections on: the canonical message type carried.
        fields: From expand-selections on: every leaf path carried, in serialization order
            (the paper's extended specification).
        spots: Locations of individual attributes (``include[0]``, ``exclude[1]``, ...).
    """

    source: Endpoint
    destination: Endpoint
    location: SourceLocation
    carries: FieldSelection = FieldSelection()
    message: str | None = None
    fields: tuple[str, ...] | None = None
    spots: Mapping[str, SourceLocation] = field(default_factory=dict, compare=False, repr=False)


@dataclass(frozen=True)
class ProjectSettings(_Spotted):
    """Project-wide settings, every one explicit (front-ends fill in the defaults).

    Attributes:
        name: Project name (used for generated entity and script names).
        fpga_part: The Xilinx part, such as ``xc7z020clg400-1``.
        fpga_family: Derived from the part: ``zynq`` or ``zynquplus``.
        middleware: ROS 1 or ROS 2, for every converter of the project.
        distro: The type store messages resolve in (noetic, humble, ...).
        bus_width: Bits of the DMA AXI-Streams: 8, 32 or 64.
        clock_mhz: Clock of the logic; durations in the spec convert to cycles with it.
        scheduler: The PL→PS scheduling algorithm, or ``auto``.
        msg_paths: Absolute directories of the user's own ``.msg`` definitions.
        spec_file: The specification the design was read from.
        maxima: The largest strings and sequences the logic accepts (sizes its counters and
            buffers).
        location: Where the project was declared.
        spots: Locations of individual attributes.
    """

    name: str
    fpga_part: str
    fpga_family: str
    middleware: Middleware
    distro: str
    bus_width: int
    clock_mhz: float
    scheduler: str
    msg_paths: tuple[Path, ...]
    spec_file: Path
    location: SourceLocation
    maxima: Limits = field(default_factory=Limits)
    spots: Mapping[str, SourceLocation] = field(default_factory=dict, compare=False, repr=False)

    @property
    def spec_dir(self) -> Path:
        """The directory relative paths of the spec are resolved against."""
        return self.spec_file.parent


@dataclass(frozen=True)
class Design:
    """The whole system: the root of the IR.

    Attributes:
        project: Project-wide settings.
        accelerators: Accelerator types in declaration order.
        blocks: Blocks in declaration order (which also numbers converters).
        connections: Connections, grouped by source block in block order.
        stage: How far the pipeline has got.
        infrastructure: From derive-infrastructure on: everything the spec leaves implicit.
    """

    project: ProjectSettings
    accelerators: tuple[AcceleratorType, ...]
    blocks: tuple[Block, ...]
    connections: tuple[Connection, ...]
    stage: Stage = Stage.PARSED
    infrastructure: Infrastructure | None = None

    def block(self, name: str) -> Block:
        """Return the block with this name."""
        for candidate in self.blocks:
            if candidate.name == name:
                return candidate
        raise KeyError(name)

    def accelerator(self, name: str) -> AcceleratorType:
        """Return the accelerator type with this name."""
        for candidate in self.accelerators:
            if candidate.name == name:
                return candidate
        raise KeyError(name)

    def blocks_of(self, kind: BlockKind) -> tuple[Block, ...]:
        """Return the blocks of one kind, in declaration order."""
        return tuple(b for b in self.blocks if b.kind is kind)
