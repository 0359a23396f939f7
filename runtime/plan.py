"""The processor's view of a system, as data: where every message goes.

Messages enter from ROS topics (the declared subscribers) and from the logic (PL→PS chunks by
publisher id); they leave to ROS topics (the declared publishers), to the logic (PS→PL chunks by
subscriber id) and to ROS-SW accelerators. A `Route` is one such destination. The plan is read
from a JSON document that ``rfc build`` derives from the holistic model (``sw/<node>_plan.json``,
written by `rfc.lower.runtime_plan`): ids, routes, message layouts and definitions, the
maxima of the logic, the ROS-SW functions' modules. Nothing here needs the compiler, so the
node ships without it.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rfc.errors import RfcError
from rfc.messages.layout_model import Layout, Middleware, layout_from_json
from rfc.messages.limits import Limits, limits_from_json
from rfc.runtime.messages import MessageObjects
from rfc.runtime.shaping import Shaper
from rfc.runtime.software import Function, SoftwareAccelerator, SoftwareBlock

#: Version of the plan document this runtime reads.
PLAN_FORMAT = 1


@dataclass(frozen=True)
class TopicBlock:
    """A declared subscriber or publisher: its block, its topic and the message type on it."""

    block: str
    topic: str
    message: str


@dataclass(frozen=True)
class ToTopic(TopicBlock):
    """Publish on a ROS topic (a declared publisher), shaped as its input port selects."""

    shaper: Shaper


@dataclass(frozen=True)
class LogicInput:
    """A subscriber converter in the logic; as a route: send to it, as PS→PL chunks of its id.

    Attributes:
        id: The ``id`` of the PS→PL chunks it takes.
        block: Its block.
        message: The message type it takes.
        layout: The layout it accepts.
    """

    id: int
    block: str
    message: str
    layout: Layout


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


Route = ToTopic | LogicInput | ToSoftware


@dataclass(frozen=True)
class TopicInput(TopicBlock):
    """A declared subscriber and where its messages go."""

    routes: tuple[Route, ...]


@dataclass(frozen=True)
class LogicFiles:
    """The build's logic, for the simulated transport: file list, top entity, bus width."""

    files: str
    top: str
    bus_width: int
    clock_mhz: float


class RuntimePlan:
    """Routes of every message source of a system, read from its plan document.

    Args:
        document: The plan (`rfc.lower.runtime_plan.plan_document`).
        base: The folder relative paths of the document (ROS-SW modules, the logic's file
            list) start from: the plan file's folder.

    Attributes:
        document: The plan as read.
        project: The project's name; ``node_name`` its ROS node's.
        middleware: ROS 1 or ROS 2.
        messages: (De)serialization of the plan's message types (for ROS-SW accelerators).
        maxima: Longest strings and sequences the logic accepts.
        max_transfer: Bytes of the largest PL→PS transfer (header included).
        inputs: The declared subscribers, in declaration order.
        outputs: The declared publishers, in declaration order.
        logic_inputs: The subscriber converters in the logic, by id.
        logic_outputs: Where each publisher id's messages go.
        software_outputs: Where each output port of each ROS-SW block sends its messages.
        subscriber_names: Name of each subscriber id (for the account).
        publisher_names: Name of each publisher id.
        logic: The logic's files, when the build wrote them.

    Raises:
        RfcError: The document is of another format version.
    """

    def __init__(self, document: dict[str, Any], base: Path | None = None) -> None:
        if document.get("format") != PLAN_FORMAT:
            raise RfcError(
                f"the runtime plan is of format {document.get('format')}, this runtime reads "
                f"format {PLAN_FORMAT}",
                hint="rebuild the system with the rfc this runtime comes from",
            )
        self.document = document
        self.base = base or Path.cwd()
        self.project: str = document["project"]
        self.node_name: str = document["node_name"]
        self.middleware = Middleware(document["middleware"])
        self.messages = MessageObjects(self.middleware, document["messages"])
        self.maxima: Limits = limits_from_json(document["maxima"])
        self.max_transfer: int = document["max_transfer"]
        self.logic_inputs = tuple(
            LogicInput(s["id"], s["block"], s["message"], layout_from_json(s["layout"]))
            for s in document["subscribers"]
        )
        self.subscriber_names = {s.id: s.block for s in self.logic_inputs}
        subscribers = {s.id: s for s in self.logic_inputs}
        self.publisher_names = {p["id"]: p["block"] for p in document["publishers"]}
        self.inputs = tuple(
            TopicInput(i["block"], i["topic"], i["message"], _routes(i["routes"], subscribers))
            for i in document["inputs"]
        )
        self.outputs = tuple(
            TopicBlock(o["block"], o["topic"], o["message"]) for o in document["outputs"]
        )
        self.logic_outputs: dict[int, tuple[Route, ...]] = {
            p["id"]: _routes(p["routes"], subscribers) for p in document["publishers"]
        }
        self.software_blocks = {
            s["block"]: SoftwareBlock(
                s["block"],
                s["module"],
                s["function"],
                tuple(s["inputs"]),
                tuple(o["name"] for o in s["outputs"]),
                tuple(o["message"] for o in s["outputs"]),
            )
            for s in document["software"]
        }
        self.software_outputs: dict[str, tuple[tuple[Route, ...], ...]] = {
            s["block"]: tuple(_routes(o["routes"], subscribers) for o in s["outputs"])
            for s in document["software"]
        }
        logic = document.get("logic")
        self.logic = None if logic is None else LogicFiles(**logic)

    def software_accelerators(self) -> dict[str, SoftwareAccelerator]:
        """Fresh instances of the ROS-SW accelerators (their input slots empty).

        Raises:
            RfcError: A function's module is missing, fails to import, or lacks the function.
        """
        return {
            name: SoftwareAccelerator(block, self.function_of(name))
            for name, block in self.software_blocks.items()
        }

    def function_of(self, block: str) -> Function:
        """The function a ROS-SW block runs, imported from its module beside the plan."""
        spec = self.software_blocks[block]
        return function_in_file(self.base / spec.module, spec.function, block)

    @property
    def has_logic(self) -> bool:
        """Whether any part of the system is in the logic."""
        return bool(self.logic_inputs or self.logic_outputs)


def load_plan(path: Path) -> RuntimePlan:
    """Read a plan file written by ``rfc build`` (relative paths start beside it).

    Raises:
        RfcError: The file cannot be read or is not a plan.
    """
    try:
        document = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise RfcError(
            f"cannot read the runtime plan '{path}': {exc}",
            hint="run the node from its build's sw/ folder, as rfc build wrote it",
        ) from None
    return RuntimePlan(document, path.parent)


def function_in_file(path: Path, name: str, block: str) -> Function:
    """Import `path` as a module and return its function `name` (for ROS-SW block `block`).

    Raises:
        RfcError: The file is missing, fails to import, or defines no such callable.
    """
    module_name = f"_rfc_sw_{abs(hash(str(path.resolve())))}"
    module = sys.modules.get(module_name)
    if module is None:
        spec = importlib.util.spec_from_file_location(module_name, path)
        if spec is None or spec.loader is None or not path.is_file():
            raise RfcError(
                f"ROS-SW accelerator '{block}' runs '{path.name}', which is not at {path}",
                hint="keep the modules rfc build copied beside the plan",
            )
        module = importlib.util.module_from_spec(spec)
        sys.path.insert(0, str(path.resolve().parent))
        try:
            spec.loader.exec_module(module)
        except Exception as exc:  # the user's module failed to import: report it
            raise RfcError(
                f"importing '{path.name}' for ROS-SW accelerator '{block}' raised "
                f"{type(exc).__name__}: {exc}",
                hint="install what the module imports on this machine",
            ) from None
        sys.modules[module_name] = module
    function: Callable[..., Any] | None = getattr(module, name, None)
    if not callable(function):
        raise RfcError(f"'{path.name}' defines no function '{name}' for ROS-SW '{block}'")
    return function


def _routes(
    documents: list[dict[str, Any]], subscribers: dict[int, LogicInput]
) -> tuple[Route, ...]:
    """The routes of `documents`; one to the logic is its converter among `subscribers` (by id)."""
    return tuple(_route(d, subscribers) for d in documents)


def _route(document: dict[str, Any], subscribers: dict[int, LogicInput]) -> Route:
    kind = document["to"]
    if kind == "logic":
        return subscribers[document["subscriber"]]
    shaper = Shaper(layout_from_json(document["layout"]))
    if kind == "topic":
        return ToTopic(document["publisher"], document["topic"], document["message"], shaper)
    return ToSoftware(
        document["block"], document["port"], document["port_name"], document["message"], shaper
    )
