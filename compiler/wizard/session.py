"""The wizard's questions, in order, each with the default that keeps the system valid.

Enter at every prompt gives the starter system: one subscriber of `STARTER_MESSAGE` → one ROS-SW
pass-through (whose reference stub the wizard writes) → one publisher. Accelerators whose source
files do not exist yet get skeletons (`rfc stub`), when the user agrees.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from rfc.errors import RfcError, SourceLocation
from rfc.ir.model import SCHEDULER_ALGORITHMS
from rfc.messages.rosbags_adapter import MessageTypes, Middleware
from rfc.messages.selection import validate_pattern
from rfc.spec import common
from rfc.wizard.connections import propose
from rfc.wizard.model import (
    AcceleratorAnswers,
    BlockAnswers,
    ConnectionAnswer,
    PortAnswer,
    ProjectAnswers,
    SystemAnswers,
)
from rfc.wizard.prompts import Prompter
from rfc.wizard.tree import message_tree

STARTER_MESSAGE = "geometry_msgs/Point"
_NAME = re.compile(r"^[A-Za-z](?:_?[A-Za-z0-9])*$")
_SOURCE_SUFFIX = {"ROS-SW": ".py", "MyHDL": ".py", "VHDL": ".vhd", "HLS": ".cpp"}


@dataclass(frozen=True)
class Session:
    """One run of the questions.

    Attributes:
        prompter: Asks the questions.
        base: The folder the spec is written to: answers' paths are relative to it.
    """

    prompter: Prompter
    base: Path

    def run(self, recommend: Callable[[SystemAnswers], tuple[str, str] | None]) -> SystemAnswers:
        """Ask everything; `recommend` gives the DSE's scheduler and reason for a draft."""
        ask = self.prompter.ask
        self.prompter.note("Project")
        name = ask("Project name", "Starter", _name)
        middleware = ask("Middleware (ROS1, ROS2)", "ROS2", _middleware)
        distro = ask(f"{middleware.label} distro", _default_distro(middleware), _distro(middleware))
        part = ask("FPGA part", common.DEFAULT_FPGA_PART, _part)
        clock = ask("Clock (MHz)", "100", _clock)
        width = ask("DMA bus width (8, 32, 64)", "64", _width)
        msg_paths = ask("Your own .msg/.idl directories (comma-separated)", "", self._directories)
        bags = ask("Bags whose message definitions to offer (comma-separated)", "", self._bags)
        types = MessageTypes(
            middleware, distro, [self.base / p for p in msg_paths], [self.base / b for b in bags]
        )
        names = sorted({n.replace("/msg/", "/") for n in types.names()})
        subscribers = self._converters("subscriber", types, names, STARTER_MESSAGE, "/input")
        accelerators, instances = self._accelerators(types, names, subscribers[0].message)
        last_output = accelerators[-1].outputs[0].message
        publishers = self._converters("publisher", types, names, last_output, "/output")
        blocks = (*subscribers, *instances, *publishers)
        connections = self._connections(types, accelerators, blocks)
        project = ProjectAnswers(
            name, middleware.value, distro, part, clock, width, msg_paths, "auto"
        )
        draft = SystemAnswers(project, accelerators, blocks, connections)
        scheduler = self._scheduler(draft, recommend)
        return replace(draft, project=replace(project, scheduler=scheduler))

    def _converters(
        self, kind: str, types: MessageTypes, names: list[str], message: str, topic: str
    ) -> tuple[BlockAnswers, ...]:
        ask = self.prompter.ask
        suffix = "sub" if kind == "subscriber" else "pub"
        found: list[BlockAnswers] = []
        while True:
            index = len(found)
            self.prompter.note(f"{kind.capitalize()} {index + 1}")
            default_name = f"{topic.strip('/')}{index or ''}_{suffix}"
            name = ask(f"{kind.capitalize()} name", default_name, _name)
            chosen = ask("Message type (Tab completes)", message, _message(types), complete=names)
            self.prompter.note(message_tree(types, types.resolve(chosen)))
            include: tuple[str, ...] = ()
            if kind == "subscriber":
                include = ask(
                    "Fields to pass on (dotted paths, * wildcards; Enter: all)",
                    "",
                    _fields(types, chosen),
                )
            block_topic = ask("Topic", f"{topic}{index or ''}", _topic)
            period = ask("Period (such as 10 ms, or cycles; Enter: none)", "", _period)
            found.append(BlockAnswers(name, kind, chosen, block_topic, "", period, include))
            if not self.prompter.ask_yes(f"Add another {kind}?", False):
                return tuple(found)

    def _accelerators(
        self, types: MessageTypes, names: list[str], message: str
    ) -> tuple[tuple[AcceleratorAnswers, ...], tuple[BlockAnswers, ...]]:
        ask = self.prompter.ask
        kinds = ", ".join(_SOURCE_SUFFIX)
        accelerators: list[AcceleratorAnswers] = []
        blocks: list[BlockAnswers] = []
        while True:
            self.prompter.note(f"Accelerator {len(accelerators) + 1}")
            type_name = ask("Accelerator type name", f"PassThrough{len(accelerators) or ''}", _name)
            kind = ask(f"Kind ({kinds})", "ROS-SW", _kind)
            inputs = ask(
                "Input ports (name:type, comma-separated)",
                f"in0:{message}",
                _ports(types),
                complete=names,
            )
            outputs = ask(
                "Output ports (name:type, comma-separated)",
                f"out0:{inputs[0].message}",
                _ports(types),
                complete=names,
            )
            function = _snake(type_name)
            sources = ask("Source file", f"./{function}{_SOURCE_SUFFIX[kind]}", self._source(kind))
            skeleton = not (self.base / sources).exists() and self.prompter.ask_yes(
                f"{sources} does not exist yet; write a skeleton there?", True
            )
            top = ask("Top (function or entity; Enter: the type name)", "", _optional)
            reference_default = f"{sources}:{top or type_name}" if kind == "ROS-SW" else ""
            reference = ask("Python reference (file.py:function)", reference_default, _optional)
            block = ask("Block name of this accelerator", f"{function}_acc", _name)
            accelerators.append(
                AcceleratorAnswers(
                    type_name, kind, sources, top, reference, inputs, outputs, skeleton
                )
            )
            blocks.append(BlockAnswers(block, "accelerator", accelerator=type_name))
            message = outputs[0].message
            if not self.prompter.ask_yes("Add another accelerator?", False):
                return tuple(accelerators), tuple(blocks)

    def _connections(
        self,
        types: MessageTypes,
        accelerators: tuple[AcceleratorAnswers, ...],
        blocks: tuple[BlockAnswers, ...],
    ) -> tuple[ConnectionAnswer, ...]:
        proposal = propose(types, accelerators, blocks)
        known = {b.name for b in blocks}
        return self.prompter.ask(
            "Connections (source[.port]>destination[.port], comma-separated)",
            ", ".join(_connection_text(c) for c in proposal),
            _connections(known),
        )

    def _scheduler(
        self,
        draft: SystemAnswers,
        recommend: Callable[[SystemAnswers], tuple[str, str] | None],
    ) -> str:
        default = "LRU"
        if any(b.period for b in draft.blocks):
            found = recommend(draft)
            if found is not None:
                default, reason = found
                self.prompter.note(f"rfc dse recommends {default}: {reason}")
        choices = ", ".join(SCHEDULER_ALGORITHMS)
        return self.prompter.ask(f"Scheduler ({choices})", default, _scheduler)

    def _source(self, kind: str) -> Callable[[str, SourceLocation], str]:
        """A source path: one that does not exist yet gets its skeleton (`rfc stub`)."""

        def check(text: str, location: SourceLocation) -> str:
            return _text(text, location)

        return check

    def _directories(self, text: str, location: SourceLocation) -> tuple[str, ...]:
        hint = "give folders that hold <package>/msg/<Name>.msg files"
        return self._existing(text, location, Path.is_dir, "'{}' is not a directory", hint)

    def _bags(self, text: str, location: SourceLocation) -> tuple[str, ...]:
        return self._existing(text, location, Path.is_file, "bag '{}' does not exist")

    def _existing(
        self,
        text: str,
        location: SourceLocation,
        exists: Callable[[Path], bool],
        problem: str,
        hint: str | None = None,
    ) -> tuple[str, ...]:
        """Comma-separated paths relative to the base, each one `exists` accepts."""
        found = _list(text)
        for entry in found:
            if not exists(self.base / entry):
                raise RfcError(
                    f"{problem.format(entry)} (paths are relative to {self.base})",
                    location=location,
                    hint=hint,
                )
        return found


def _list(text: str) -> tuple[str, ...]:
    return tuple(part.strip() for part in text.split(",") if part.strip())


def _name(text: str, location: SourceLocation) -> str:
    if not _NAME.match(text):
        raise RfcError(
            f"'{text}' is not a valid name; expected a letter, then letters, digits and "
            "single underscores",
            location=location,
        )
    return text


def _text(text: str, location: SourceLocation) -> str:
    if not text:
        raise RfcError("an answer is needed here", location=location)
    return text


def _optional(text: str, location: SourceLocation) -> str:
    return text


def _middleware(text: str, location: SourceLocation) -> Middleware:
    return common.middleware(text, location)


def _default_distro(middleware: Middleware) -> str:
    return common.distro(None, middleware, SourceLocation("wizard", 0, 0))


def _distro(middleware: Middleware) -> Callable[[str, SourceLocation], str]:
    def check(text: str, location: SourceLocation) -> str:
        return common.distro(text, middleware, location)

    return check


def _part(text: str, location: SourceLocation) -> str:
    common.fpga_family(text, location)
    return text


def _clock(text: str, location: SourceLocation) -> float:
    try:
        value = float(text)
    except ValueError:
        raise RfcError(f"'{text}' is not a number of MHz", location=location) from None
    return common.clock_mhz(value, location)


def _width(text: str, location: SourceLocation) -> int:
    if not text.isdigit():
        raise RfcError(f"bus width must be 8, 32 or 64 bits, not '{text}'", location=location)
    return common.bus_width(int(text), location)


def _message(types: MessageTypes) -> Callable[[str, SourceLocation], str]:
    def check(text: str, location: SourceLocation) -> str:
        try:
            types.resolve(text)
        except RfcError as exc:
            raise RfcError(exc.message, location=location, hint=exc.hint) from None
        return text

    return check


def _fields(types: MessageTypes, message: str) -> Callable[[str, SourceLocation], tuple[str, ...]]:
    from rfc.messages.layout import flatten

    def check(text: str, location: SourceLocation) -> tuple[str, ...]:
        patterns = _list(text)
        layout = flatten(types, types.resolve(message))
        for pattern in patterns:
            validate_pattern(layout, pattern, location)
        return patterns

    return check


def _topic(text: str, location: SourceLocation) -> str:
    if not text.startswith("/") or " " in text:
        raise RfcError(f"topic '{text}' must start with '/' and hold no space", location=location)
    return text


def _period(text: str, location: SourceLocation) -> str:
    if text:
        common.cycles(int(text) if text.isdigit() else text, 100.0, "period", location)
    return text


def _kind(text: str, location: SourceLocation) -> str:
    return common.accelerator_kind(text, location).value


def _ports(types: MessageTypes) -> Callable[[str, SourceLocation], tuple[PortAnswer, ...]]:
    check_message = _message(types)

    def check(text: str, location: SourceLocation) -> tuple[PortAnswer, ...]:
        ports = []
        for entry in _list(text):
            name, colon, message = entry.partition(":")
            if not colon:
                raise RfcError(
                    f"port '{entry}' needs a name and a type", location=location, hint="name:type"
                )
            ports.append(
                PortAnswer(_name(name.strip(), location), check_message(message, location))
            )
        if not ports:
            raise RfcError("an accelerator needs at least one port here", location=location)
        return tuple(ports)

    return check


def _connections(known: set[str]) -> Callable[[str, SourceLocation], tuple[ConnectionAnswer, ...]]:
    def check(text: str, location: SourceLocation) -> tuple[ConnectionAnswer, ...]:
        found = []
        for entry in _list(text):
            source, arrow, destination = (part.strip() for part in entry.partition(">"))
            origin, _, output = source.partition(".")
            block, _, port = destination.partition(".")
            for name in (origin, block):
                if not arrow or name not in known:
                    raise RfcError(
                        f"connection '{entry}' must join two blocks of the system",
                        location=location,
                        hint=f"the blocks are {', '.join(sorted(known))}",
                    )
            found.append(ConnectionAnswer(origin, block, port, output))
        return tuple(found)

    return check


def _connection_text(connection: ConnectionAnswer) -> str:
    output = f".{connection.output}" if connection.output else ""
    port = f".{connection.port}" if connection.port else ""
    return f"{connection.source}{output}>{connection.destination}{port}"


def _scheduler(text: str, location: SourceLocation) -> str:
    return common.scheduler(text, location)


def _snake(name: str) -> str:
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()
