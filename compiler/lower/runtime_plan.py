"""The runtime plan: the processor side of a design, derived from the holistic model as data.

`plan_document` lists ids, routes (using the placement of `rfc.ir.infrastructure`: a
subscriber in the logic gets its messages once, the logic fans out; a crossing converter carries
a connection between a hardware and a software accelerator), the layouts that shape and check
frames, the definition of every message type, the logic's maxima and the ROS-SW functions. The
generated node reads it (`rfc.runtime.plan`), and so does `rfc sim` through `DesignPlan`: what
is simulated is what is deployed.
"""

from __future__ import annotations

import inspect
from pathlib import Path
from typing import Any

from rfc.errors import RfcError
from rfc.ir.infrastructure import CHUNK_HEADER_BYTES, Converter
from rfc.ir.model import AcceleratorType, BlockKind, Connection, Design
from rfc.messages.layout import Layout, flatten
from rfc.messages.layout_model import layout_to_json
from rfc.messages.limits import limits_to_json
from rfc.passes.base import types_of
from rfc.runtime.plan import PLAN_FORMAT, RuntimePlan
from rfc.runtime.software import Function
from rfc.spec.python_sources import function_in

_ROLE = "ROS-SW accelerator"


def node_name(design: Design) -> str:
    """The ROS node name: the project name in snake case."""
    name = design.project.name
    return "".join(f"_{c.lower()}" if c.isupper() and i else c.lower() for i, c in enumerate(name))


def function_source(accelerator: AcceleratorType) -> tuple[Path, str]:
    """The Python file and function a ROS-SW accelerator runs.

    The accelerator's Python reference when it names one (so that a hardware accelerator
    switched to ROS-SW runs its reference model), else ``top`` in its Python source, else a
    function named like the accelerator type there.

    Raises:
        RfcError: Neither a Python reference nor a Python source names a function.
    """
    function = accelerator.reference_function
    if function is not None and not inspect.isfunction(function):
        # a C simulation `rfc sim` attached to an HLS accelerator: it runs from its sources
        return accelerator.sources[0], accelerator.top or accelerator.name
    if function is not None:
        source = inspect.getsourcefile(function)
        assert source is not None, "a Python spec's reference is defined in a file"
        return Path(source), function.__name__
    if accelerator.reference is not None:
        return accelerator.reference.file, accelerator.reference.name
    python = next((p for p in accelerator.sources if p.suffix == ".py"), None)
    if python is None:
        raise RfcError(
            f"accelerator '{accelerator.name}' runs as ROS-SW but has neither a Python "
            "reference nor a Python source to run",
            location=accelerator.location,
            hint="name its Python model with 'reference: file.py:function'",
        )
    return python, accelerator.top or accelerator.name


def plan_document(design: Design, *, logic_files: str | None = None) -> dict[str, Any]:
    """The runtime plan of a design at stage DERIVED.

    Args:
        design: The holistic model.
        logic_files: The logic's file list relative to the plan (when the build writes it).

    Raises:
        RfcError: A ROS-SW accelerator names no function.
    """
    return _Planner(design).document(logic_files)


class DesignPlan(RuntimePlan):
    """The runtime plan of a design in memory (``rfc sim``), keeping the model beside it.

    Attributes:
        design: The holistic model.
        types: Its message definitions (the compiler's view, for tests and replay).
    """

    def __init__(self, design: Design) -> None:
        self.design = design
        self.types = types_of(design.project)
        super().__init__(plan_document(design), design.project.spec_dir)

    def function_of(self, block: str) -> Function:
        """The function, found as the spec names it (a Python spec may hold it in memory)."""
        kind = self.design.accelerator(self.design.block(block).accelerator or "")
        if kind.reference_function is not None:
            return kind.reference_function
        path, name = function_source(kind)
        return function_in(path, name, kind, _ROLE)


class _Planner:
    def __init__(self, design: Design) -> None:
        infrastructure = design.infrastructure
        assert infrastructure is not None, "plan a design at stage DERIVED"
        self.design = design
        self.infrastructure = infrastructure
        self.types = types_of(design.project)
        self.software = set(infrastructure.software)
        self.crossing_subscribers = {
            c.crossing.hardware: c for c in infrastructure.subscribers if c.crossing is not None
        }
        self.logic_subscribers = {
            c.block: c for c in infrastructure.subscribers if c.crossing is None
        }
        self.message_types: set[str] = set()

    def document(self, logic_files: str | None) -> dict[str, Any]:
        design, infrastructure = self.design, self.infrastructure
        project = design.project
        document: dict[str, Any] = {
            "format": PLAN_FORMAT,
            "project": project.name,
            "node_name": node_name(design),
            "middleware": project.middleware.value,
            "maxima": limits_to_json(project.maxima),
            "max_transfer": CHUNK_HEADER_BYTES
            + max((c.max_frame_bytes for c in infrastructure.publishers), default=0),
            "subscribers": [
                {
                    "id": c.id,
                    "block": c.block,
                    "message": self._type(c.message),
                    "layout": layout_to_json(c.layout),
                }
                for c in infrastructure.subscribers
            ],
            "publishers": [
                {"id": c.id, "block": c.block, "routes": self._publisher_routes(c)}
                for c in infrastructure.publishers
            ],
            "inputs": [
                {
                    "block": b.name,
                    "topic": b.topic or "",
                    "message": self._type(b.message or ""),
                    "routes": self._subscriber_routes(b.name),
                }
                for b in design.blocks_of(BlockKind.SUBSCRIBER)
            ],
            "outputs": [
                {"block": b.name, "topic": b.topic or "", "message": self._type(b.message or "")}
                for b in design.blocks_of(BlockKind.PUBLISHER)
            ],
            "software": [self._software_block(name) for name in infrastructure.software],
            "logic": None,
        }
        if logic_files is not None and (infrastructure.subscribers or infrastructure.publishers):
            from rfc.lower.system.generate import top_name

            document["logic"] = {
                "files": logic_files,
                "top": top_name(design),
                "bus_width": project.bus_width,
                "clock_mhz": project.clock_mhz,
            }
        document["messages"] = {
            name: dict(zip(("definition", "md5"), self.types.definition(name), strict=True))
            for name in sorted(self.message_types)
        }
        return document

    def _type(self, name: str) -> str:
        canonical = self.types.resolve(name)
        self.message_types.add(canonical)
        return canonical

    def _software_block(self, name: str) -> dict[str, Any]:
        block = self.design.block(name)
        module, function = function_source(self.design.accelerator(block.accelerator or ""))
        return {
            "block": name,
            "module": module.name,
            "function": function,
            "inputs": [p.name for p in block.inputs],
            "outputs": [
                {
                    "name": port.name,
                    "message": self._type(port.message),
                    "routes": self._routes_from(name, port.name),
                }
                for port in block.outputs
            ],
        }

    def _subscriber_routes(self, name: str) -> list[dict[str, Any]]:
        routes: list[dict[str, Any]] = []
        converter = self.logic_subscribers.get(name)
        if converter is not None:
            routes.append(_to_logic(converter))
        routes.extend(self._routes_from(name, None, software_only=True))
        return routes

    def _publisher_routes(self, converter: Converter) -> list[dict[str, Any]]:
        if converter.crossing is None:
            block = self.design.block(converter.block)
            layout = flatten(self.types, converter.message)  # the logic already shaped it
            return [self._to_topic(block.name, block.topic or "", layout)]
        routes = []
        for target in converter.crossing.software:
            software_block, _, port = target.partition(".")
            routes.append(self._to_software(software_block, port))
        return routes

    def _routes_from(
        self, block: str, port: str | None, *, software_only: bool = False
    ) -> list[dict[str, Any]]:
        return [
            self._route(connection)
            for connection in self.design.connections
            if connection.source.block == block
            and (port is None or connection.source.port == port)
            and (not software_only or connection.destination.block in self.software)
        ]

    def _route(self, connection: Connection) -> dict[str, Any]:
        destination = self.design.block(connection.destination.block)
        port = connection.destination.port or ""
        if destination.kind is BlockKind.PUBLISHER:
            layout = destination.port(port).layout
            assert layout is not None
            return self._to_topic(destination.name, destination.topic or "", layout)
        if destination.name in self.software:
            return self._to_software(destination.name, port)
        return _to_logic(self.crossing_subscribers[f"{destination.name}.{port}"])

    def _to_topic(self, publisher: str, topic: str, layout: Layout) -> dict[str, Any]:
        return {
            "to": "topic",
            "publisher": publisher,
            "topic": topic,
            "message": self._type(layout.type_name),
            "layout": layout_to_json(layout),
        }

    def _to_software(self, block_name: str, port_name: str) -> dict[str, Any]:
        block = self.design.block(block_name)
        port = block.port(port_name)
        assert port.layout is not None
        return {
            "to": "software",
            "block": block_name,
            "port": [p.name for p in block.inputs].index(port_name),
            "port_name": port_name,
            "message": self._type(port.message),
            "layout": layout_to_json(port.layout),
        }


def _to_logic(converter: Converter) -> dict[str, Any]:
    return {"to": "logic", "subscriber": converter.id, "block": converter.block}
