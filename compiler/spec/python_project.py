"""The Python front-end: accelerators as annotated MyHDL blocks, a system as a `Project`.

    import rfc

    @rfc.accelerator(inputs={"q": "geometry_msgs/Quaternion"},
                     outputs={"euler": "geometry_msgs/Point"}, reference=quat_to_euler)
    @block
    def QuaternionToEuler(clk, ...):
        ...

    project = rfc.Project("RotationConverterNode", middleware="ROS2")
    imu = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
    acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
    pub = project.publisher("Euler_pub", "geometry_msgs/Point")
    imu >> acc >> pub                     # acc["q"] names a port; .include(...) selects

Every call records the user's call site, so the passes report errors at the line of the
``>>`` or the ``project.subscriber(...)`` responsible, exactly as they report YAML lines.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from rfc.errors import RfcError, SourceLocation, did_you_mean
from rfc.ir.model import (
    AcceleratorType,
    Block,
    BlockKind,
    Connection,
    Design,
    Endpoint,
    FieldSelection,
    ProjectSettings,
)
from rfc.messages.limits import Limits
from rfc.spec import common
from rfc.spec.python_accelerators import AcceleratorDefinition
from rfc.spec.python_calls import as_text, as_texts, call_site


class _Source:
    """The sending side of a `>>`: a block, maybe one of its ports, maybe a selection."""

    _project: Project
    _block: str
    _port: str | None = None
    _carries: FieldSelection = FieldSelection()

    def include(self, *paths: str) -> Selection:
        """Carry only these fields over the next ``>>`` (dotted paths, ``*`` wildcards)."""
        location, _ = call_site()
        return self._narrowed(FieldSelection(include=as_texts(paths, "include", location)))

    def exclude(self, *paths: str) -> Selection:
        """Do not carry these fields over the next ``>>``."""
        location, _ = call_site()
        return self._narrowed(FieldSelection(exclude=as_texts(paths, "exclude", location)))

    def _narrowed(self, more: FieldSelection) -> Selection:
        """This source with the patterns of `more` added to its own."""
        return Selection(self._project, self._block, self._port, self._carries + more)

    def __rshift__(self, destination: Any) -> BlockHandle:
        """Connect to a block, a block's port (``acc["q"]``) or a selection of one."""
        location, _ = call_site()
        return self._project._connect(self, destination, location)


class BlockHandle(_Source):
    """A block of a `Project`: connect it with ``>>``; ``handle["port"]`` names a port."""

    def __init__(self, project: Project, name: str) -> None:
        self._project, self._block = project, name

    @property
    def name(self) -> str:
        """The block's name."""
        return self._block

    def __getitem__(self, port_name: str) -> PortHandle:
        return PortHandle(self._project, self._block, port_name)

    def __repr__(self) -> str:
        return f"<rfc block {self._block}>"


class PortHandle(_Source):
    """One port of a block."""

    def __init__(self, project: Project, block: str, port_name: str) -> None:
        self._project, self._block, self._port = project, block, port_name


class Selection(_Source):
    """A block or port with the fields the next ``>>`` carries."""

    def __init__(
        self,
        project: Project,
        block: str,
        port_name: str | None,
        carries: FieldSelection,
    ) -> None:
        self._project, self._block, self._port = project, block, port_name
        self._carries = carries


class Project:
    """A system: subscribers, accelerators and publishers, wired with ``>>``.

    Args:
        name: Project name.
        fpga_part: Xilinx Zynq part.
        middleware: ``ROS`` (ROS 1) or ``ROS2``.
        distro: Type store (default: noetic for ROS 1, humble for ROS 2).
        bus_width: Bits of the DMA AXI-Streams: 8, 32 or 64.
        clock_mhz: Clock of the logic in MHz.
        scheduler: LRU, NPFP, PFP, ROEDF, LOEDF, LST, or auto.
        msg_paths: Directories of your own ``.msg`` files, relative to this file.
        maxima: The largest strings and sequences of the logic: ``string``, ``sequence``,
            ``frame`` and ``fields`` (a mapping of dotted paths to counts), as in the YAML form.
    """

    def __init__(
        self,
        name: str,
        *,
        fpga_part: str = common.DEFAULT_FPGA_PART,
        middleware: str = "ROS2",
        distro: str | None = None,
        bus_width: int = common.DEFAULT_BUS_WIDTH,
        clock_mhz: float = common.DEFAULT_CLOCK_MHZ,
        scheduler: str = common.DEFAULT_SCHEDULER,
        msg_paths: Iterable[str] = (),
        maxima: Mapping[str, Any] | None = None,
    ) -> None:
        location, base = call_site()
        limits, field_spots = _maxima(maxima or {}, location)
        chosen = common.middleware(as_text(middleware, "middleware", location), location)
        directories = [
            common.message_directory(text, base, location)
            for text in as_texts(msg_paths, "msg_paths", location)
        ]
        self._settings = ProjectSettings(
            name=as_text(name, "project name", location),
            fpga_part=fpga_part,
            fpga_family=common.fpga_family(as_text(fpga_part, "fpga_part", location), location),
            middleware=chosen,
            distro=common.distro(
                None if distro is None else as_text(distro, "distro", location), chosen, location
            ),
            bus_width=common.bus_width(bus_width, location),
            clock_mhz=common.clock_mhz(clock_mhz, location),
            scheduler=common.scheduler(scheduler, location),
            msg_paths=tuple(directories),
            spec_file=base / Path(location.file).name,
            location=location,
            maxima=limits,
            spots=field_spots,
        )
        self._accelerators: list[AcceleratorType] = []
        self._blocks: list[Block] = []
        self._connections: list[Connection] = []

    @property
    def name(self) -> str:
        """The project's name."""
        return self._settings.name

    def subscriber(self, name: str, message: str, **timing: Any) -> BlockHandle:
        """Add a subscriber converter (ROS>accelerator) receiving `message` on a topic.

        Keyword Args:
            topic: The ROS topic (default: ``/<name>``).
            period: Clock cycles, or a duration such as ``"10 us"``, between messages.
            deadline: Relative deadline, likewise (default: the period).
            max_bytes: Largest frame accepted (variable-size messages).
        """
        return self._converter(BlockKind.SUBSCRIBER, name, message, timing)

    def publisher(self, name: str, message: str, **timing: Any) -> BlockHandle:
        """Add a publisher converter (accelerator>ROS) sending `message`; see `subscriber`."""
        return self._converter(BlockKind.PUBLISHER, name, message, timing)

    def accelerator(self, name: str, definition: AcceleratorDefinition) -> BlockHandle:
        """Add an instance of an accelerator type defined with `accelerator`."""
        location, _ = call_site()
        if not isinstance(definition, AcceleratorDefinition):
            raise RfcError(
                f"accelerator '{name}' needs a type made with @rfc.accelerator or "
                f"rfc.external_accelerator, not {definition!r}",
                location=location,
            )
        if not any(t is definition.definition for t in self._accelerators):
            self._accelerators.append(definition.definition)
        self._blocks.append(
            Block(
                as_text(name, "block name", location),
                BlockKind.ACCELERATOR,
                location,
                accelerator=definition.definition.name,
            )
        )
        return BlockHandle(self, name)

    def connect(
        self,
        source: Any,
        destination: Any,
        *,
        include: Iterable[str] = (),
        exclude: Iterable[str] = (),
    ) -> BlockHandle:
        """Connect two blocks or ports, like ``source.include(...) >> destination``."""
        location, _ = call_site()
        if not isinstance(source, _Source):
            raise RfcError(
                f"connect() needs a block or port as source, not {source!r}", location=location
            )
        selected = source._narrowed(
            FieldSelection(
                as_texts(include, "include", location), as_texts(exclude, "exclude", location)
            )
        )
        return self._connect(selected, destination, location)

    def _converter(
        self, kind: BlockKind, name: str, message: str, timing: dict[str, Any]
    ) -> BlockHandle:
        location, _ = call_site()
        owner = f"{kind.value} '{name}'"
        unknown = sorted(set(timing) - {"topic", "period", "deadline", "max_bytes"})
        if unknown:
            raise RfcError(
                f"{owner} got unknown argument '{unknown[0]}'; expected topic, period, "
                "deadline or max_bytes",
                location=location,
            )
        clock = self._settings.clock_mhz
        period, deadline, max_bytes = (timing.get(k) for k in ("period", "deadline", "max_bytes"))
        self._blocks.append(
            Block(
                name=as_text(name, f"{kind.value} name", location),
                kind=kind,
                location=location,
                message=as_text(message, f"the message of {owner}", location),
                topic=as_text(timing.get("topic", common.default_topic(name)), "topic", location),
                period=None
                if period is None
                else common.cycles(period, clock, f"period of {owner}", location),
                deadline=None
                if deadline is None
                else common.cycles(deadline, clock, f"deadline of {owner}", location),
                max_bytes=None
                if max_bytes is None
                else common.positive(max_bytes, f"max_bytes of {owner}", location),
            )
        )
        return BlockHandle(self, name)

    def _connect(self, source: _Source, destination: Any, location: SourceLocation) -> BlockHandle:
        if not isinstance(destination, _Source):
            raise RfcError(
                f"'>>' needs a block or a port on its right, not {destination!r}",
                location=location,
            )
        for side in (source, destination):
            if side._project is not self:
                raise RfcError(
                    f"block '{side._block}' belongs to another project", location=location
                )
        carries = source._carries + destination._carries
        self._connections.append(
            Connection(
                source=Endpoint(source._block, source._port, location),
                destination=Endpoint(destination._block, destination._port, location),
                location=location,
                carries=carries,
                spots={key: location for key, _ in carries.patterns()},
            )
        )
        return BlockHandle(self, destination._block)

    def design(self) -> Design:
        """The project as IR at stage PARSED (connections grouped by source block)."""
        order = {block.name: index for index, block in enumerate(self._blocks)}
        connections = sorted(self._connections, key=lambda c: order.get(c.source.block, len(order)))
        return Design(
            self._settings, tuple(self._accelerators), tuple(self._blocks), tuple(connections)
        )


def _maxima(
    given: Mapping[str, Any], location: SourceLocation
) -> tuple[Limits, dict[str, SourceLocation]]:
    """Check the ``maxima`` argument: the YAML form's keys, all pinned to the call."""
    known = (*common.MAXIMA_KEYS, "fields")
    if not isinstance(given, Mapping):
        raise RfcError(
            f"maxima must be a mapping of {', '.join(known)}, not {given!r}", location=location
        )
    for key in given:
        if key not in known:
            raise RfcError(
                f"unknown key '{key}' in maxima; expected one of {', '.join(known)}",
                location=location,
                hint=did_you_mean(str(key), known),
            )
    fields = given.get("fields") or {}
    if not isinstance(fields, Mapping):
        raise RfcError(
            f"maxima 'fields' must map field paths to integers, not {fields!r}", location=location
        )
    limits = common.maxima(
        {key: (given[key], location) for key in common.MAXIMA_KEYS if key in given},
        {str(path): (value, location) for path, value in fields.items()},
    )
    return limits, {f"maxima.fields.{path}": location for path in fields}
