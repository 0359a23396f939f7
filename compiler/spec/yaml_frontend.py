"""The YAML front-end: a spec file in the paper's format (Listing 1, extended) becomes a Design.

It checks the shape of the document (keys, value kinds, enumerations, paths that must exist)
and records where every element was written. Everything that is about the system rather than
the document (names, types, connections) is left to the passes, which both front-ends share.
"""

from __future__ import annotations

import re
from pathlib import Path

from rfc.errors import RfcError, SourceLocation
from rfc.ir.model import (
    AcceleratorKind,
    AcceleratorType,
    Block,
    BlockKind,
    Connection,
    Design,
    Direction,
    Endpoint,
    FieldSelection,
    FunctionRef,
    Port,
    ProjectSettings,
)
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware
from rfc.spec import common
from rfc.spec.schema import (
    ACCELERATOR,
    BLOCK,
    INTERFACE,
    MAXIMA,
    OUTGOING,
    PORT,
    PROJECT,
    PUBLISHER_TYPE,
    ROOT,
    SCHEDULER,
    SUBSCRIBER_TYPE,
    ValueKind,
)
from rfc.spec.yaml_nodes import MappingReader, YamlNode, load_yaml

_CONVERTER_KEYS = ("middleware", "mode", "message", "topic", "period", "deadline", "maxBytes")
_CONVERTER_TYPES = {
    re.sub(r"\s+", "", SUBSCRIBER_TYPE).lower(): BlockKind.SUBSCRIBER,
    re.sub(r"\s+", "", PUBLISHER_TYPE).lower(): BlockKind.PUBLISHER,
}


def load_yaml_spec(path: Path, display: str | None = None) -> Design:
    """Read a YAML spec into a design at stage PARSED.

    Args:
        path: The spec file.
        display: How to name the file in locations (default: the path as given).

    Raises:
        RfcError: The document is not a well-formed spec; the message names file:line:col.
    """
    root = MappingReader(load_yaml(path, display or str(path)), ROOT, "the spec")
    return _YamlFrontend(path.resolve().parent, path.resolve()).design(root)


class _YamlFrontend:
    def __init__(self, base: Path, spec_file: Path) -> None:
        self.base = base
        self.spec_file = spec_file
        self.stated: list[tuple[Middleware, str, SourceLocation]] = []

    def design(self, root: MappingReader) -> Design:
        project = MappingReader(root.node_of("project"), PROJECT, "project")
        clock = common.clock_mhz(
            project.get("clockMHz", common.DEFAULT_CLOCK_MHZ), project.location("clockMHz")
        )
        accelerators = tuple(self._accelerator(node) for node in root.items("accelerators"))
        blocks: list[Block] = []
        connections: list[Connection] = []
        for node in root.items("blocks"):
            block, outgoing = self._block(node, clock)
            blocks.append(block)
            connections.extend(outgoing)
        settings = self._project(project, clock)
        self._check_middlewares(settings)
        return Design(settings, accelerators, tuple(blocks), tuple(connections))

    def _project(self, reader: MappingReader, clock: float) -> ProjectSettings:
        if reader.has("middleware"):
            chosen = common.middleware(reader.get("middleware"), reader.location("middleware"))
            self.stated.insert(0, (chosen, "the project", reader.location("middleware")))
        elif self.stated:
            chosen = self.stated[0][0]
        else:
            chosen = common.DEFAULT_MIDDLEWARE
        part = reader.get("fpgaPart", common.DEFAULT_FPGA_PART)
        maxima, field_spots = self._maxima(reader)
        return ProjectSettings(
            name=reader.get("name"),
            fpga_part=part,
            fpga_family=common.fpga_family(part, reader.location("fpgaPart")),
            middleware=chosen,
            distro=common.distro(reader.get("distro"), chosen, reader.location("distro")),
            bus_width=common.bus_width(
                reader.get("busWidth", common.DEFAULT_BUS_WIDTH), reader.location("busWidth")
            ),
            clock_mhz=clock,
            scheduler=self._scheduler(reader),
            msg_paths=tuple(
                common.message_directory(text, self.base, location)
                for text, location in reader.strings("msg_paths")
            ),
            spec_file=self.spec_file,
            location=reader.node.location,
            maxima=maxima,
            spots={key: reader.location(key) for key in reader.values} | field_spots,
        )

    def _maxima(self, project: MappingReader) -> tuple[Limits, dict[str, SourceLocation]]:
        """The maxima, and where each per-field one is written (a pass checks the paths)."""
        if not project.has("maxima"):
            return Limits(), {}
        reader = MappingReader(project.node_of("maxima"), MAXIMA, "maxima")
        given = {
            key: (reader.get(key), reader.location(key))
            for key in common.MAXIMA_KEYS
            if reader.has(key)
        }
        fields: dict[str, tuple[object, SourceLocation]] = {}
        spots: dict[str, SourceLocation] = {}
        if reader.has("fields"):
            for key, value in reader.node_of("fields").pairs():
                fields[str(key.value)] = (value.value, value.location)
                spots[f"maxima.fields.{key.value}"] = key.location
        return common.maxima(given, fields), spots

    def _scheduler(self, project: MappingReader) -> str:
        if not project.has("scheduler"):
            return common.DEFAULT_SCHEDULER
        node = project.node_of("scheduler")
        if node.kind is ValueKind.MAPPING:
            reader = MappingReader(node, SCHEDULER, "scheduler")
            return common.scheduler(reader.get("algorithm"), reader.location("algorithm"))
        return common.scheduler(node.value, node.location)

    def _check_middlewares(self, settings: ProjectSettings) -> None:
        if not self.stated:
            return
        _, first_owner, first_location = self.stated[0]
        for stated, owner, location in self.stated:
            if stated is not settings.middleware:
                raise RfcError(
                    f"{owner} uses {stated.label}, but {first_owner} uses "
                    f"{settings.middleware.label} (at {first_location}); a project has one "
                    "middleware",
                    location=location,
                )

    def _state_middleware(self, reader: MappingReader, owner: str) -> None:
        if reader.has("middleware"):
            location = reader.location("middleware")
            self.stated.append(
                (common.middleware(reader.get("middleware"), location), owner, location)
            )

    def _accelerator(self, node: YamlNode) -> AcceleratorType:
        reader = MappingReader(node, ACCELERATOR, "an accelerator", named="accelerator")
        name = reader.get("name")
        owner = reader.owner
        kind = common.accelerator_kind(reader.get("type"), reader.location("type"))
        sources = [
            (common.source_file(text, self.base, "source file", location), location)
            for text, location in reader.strings("sources")
        ]
        if not sources:
            raise RfcError(f"{owner} lists no source files", location=reader.location("sources"))
        common.check_source_suffixes(kind, sources, owner)
        interface = MappingReader(
            reader.node_of("interface"), INTERFACE, f"the interface of {owner}"
        )
        inputs = tuple(
            self._port(item, Direction.IN, index, owner)
            for index, item in enumerate(interface.items("input"))
        )
        outputs = tuple(
            self._port(item, Direction.OUT, index, owner)
            for index, item in enumerate(interface.items("output"))
        )
        top = reader.get("top", name if kind is AcceleratorKind.MYHDL else None)
        python_source = next((p for p, _ in sources if p.suffix == ".py"), None)
        reference: FunctionRef | None = None
        if reader.has("reference"):
            reference = common.function_ref(
                reader.get("reference"), self.base, python_source, reader.location("reference")
            )
        return AcceleratorType(
            name=name,
            kind=kind,
            sources=tuple(path for path, _ in sources),
            inputs=inputs,
            outputs=outputs,
            location=node.location,
            top=top,
            reference=reference,
            spots={key: reader.location(key) for key in reader.values},
        )

    def _port(self, node: YamlNode, direction: Direction, index: int, owner: str) -> Port:
        what = "an input" if direction is Direction.IN else "an output"
        reader = MappingReader(node, PORT, f"{what} of {owner}", named=f"port of {owner}")
        name = reader.get("name", common.default_port_name(direction.value, index))
        self._state_middleware(reader, f"port '{name}' of {owner}")
        needs, pattern_spots = _selection(reader)
        return Port(
            name=name,
            direction=direction,
            message=reader.get("message"),
            location=node.location,
            needs=needs,
            spots={key: reader.location(key) for key in reader.values} | pattern_spots,
        )

    def _block(self, node: YamlNode, clock: float) -> tuple[Block, list[Connection]]:
        reader = MappingReader(node, BLOCK, "a block", named="block")
        name = reader.get("name")
        written = reader.get("type")
        kind = _CONVERTER_TYPES.get(re.sub(r"\s+", "", str(written)).lower(), BlockKind.ACCELERATOR)
        if kind is BlockKind.ACCELERATOR:
            for key in _CONVERTER_KEYS:
                if reader.has(key):
                    raise RfcError(
                        f"'{key}' applies to subscribers and publishers, not to block '{name}' "
                        f"of accelerator type '{written}'",
                        location=reader.keys[key].location,
                        hint=f"converters have type {SUBSCRIBER_TYPE} or {PUBLISHER_TYPE}",
                    )
            block = Block(
                name,
                kind,
                node.location,
                accelerator=written,
                spots={key: reader.location(key) for key in reader.values},
            )
        else:
            block = self._converter(reader, name, kind, clock)
        outgoing = [self._connection(item, name) for item in reader.items("outgoing")]
        return block, outgoing

    def _converter(self, reader: MappingReader, name: str, kind: BlockKind, clock: float) -> Block:
        owner = f"{kind.value} '{name}'"
        mode = reader.choice("mode")
        if mode is not None and mode != kind.value:
            raise RfcError(
                f"block '{name}' has type {reader.get('type')} (a {kind.value}), but mode '{mode}'",
                location=reader.location("mode"),
                hint=f"write mode: {kind.value}, or leave it out",
            )
        if not reader.has("message"):
            raise RfcError(
                f"{owner} has no 'message'; a converter needs its message type",
                location=reader.node.location,
            )
        self._state_middleware(reader, owner)
        period = deadline = max_bytes = None
        if reader.has("period"):
            period = common.cycles(
                reader.get("period"), clock, f"period of {owner}", reader.location("period")
            )
        if reader.has("deadline"):
            deadline = common.cycles(
                reader.get("deadline"), clock, f"deadline of {owner}", reader.location("deadline")
            )
        if reader.has("maxBytes"):
            max_bytes = common.positive(
                reader.get("maxBytes"), f"maxBytes of {owner}", reader.location("maxBytes")
            )
        return Block(
            name=name,
            kind=kind,
            location=reader.node.location,
            message=reader.get("message"),
            topic=reader.get("topic", common.default_topic(name)),
            period=period,
            deadline=deadline,
            max_bytes=max_bytes,
            spots={key: reader.location(key) for key in reader.values},
        )

    def _connection(self, node: YamlNode, source: str) -> Connection:
        reader = MappingReader(node, OUTGOING, f"an outgoing entry of block '{source}'")
        carries, spots = _selection(reader)
        return Connection(
            source=Endpoint(source, reader.get("from"), reader.location("from")),
            destination=Endpoint(reader.get("name"), reader.get("port"), reader.location("name")),
            location=node.location,
            carries=carries,
            spots=spots,
        )


def _selection(reader: MappingReader) -> tuple[FieldSelection, dict[str, SourceLocation]]:
    """The include/exclude keys of a port or an outgoing entry, with where each pattern is."""
    include, exclude = reader.strings("include"), reader.strings("exclude")
    selection = FieldSelection(
        tuple(text for text, _ in include), tuple(text for text, _ in exclude)
    )
    locations = [location for _, location in (*include, *exclude)]
    keys = [key for key, _ in selection.patterns()]
    return selection, dict(zip(keys, locations, strict=True))
