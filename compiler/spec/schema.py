"""The YAML spec format as data: every section, its keys, their value kinds.

One table serves three purposes: the YAML front-end checks keys and value kinds against it
(unknown keys get a did-you-mean), `json_schema()` renders it as the JSON Schema shipped in
``docs/spec.schema.json`` (a test keeps the two equal), and docs/spec.md describes it.
Regenerate the schema file with ``python -m rfc.spec.schema > docs/spec.schema.json``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from rfc.ir.model import SCHEDULER_ALGORITHMS, AcceleratorKind


class ValueKind(StrEnum):
    """The YAML kinds a key's value may take; the names are the ones error messages use."""

    STRING = "a string"
    INTEGER = "an integer"
    NUMBER = "a number"
    BOOLEAN = "a boolean"
    MAPPING = "a mapping"
    LIST = "a list"
    STRING_LIST = "a list of strings"
    COUNTS = "a mapping of field paths to integers"


@dataclass(frozen=True)
class Key:
    """One key of a section.

    Attributes:
        name: The key as written.
        kinds: The value kinds accepted.
        description: One sentence for the docs and the schema.
        required: Whether the key must be present.
        choices: The values accepted, when it is an enumeration (case-insensitive).
        section: The section of a mapping value, or of each element of a list value.
    """

    name: str
    kinds: tuple[ValueKind, ...]
    description: str
    required: bool = False
    choices: tuple[str | int, ...] = ()
    section: Section | None = None


@dataclass(frozen=True)
class Section:
    """A mapping of the spec: its name in messages and its keys."""

    name: str
    description: str
    keys: tuple[Key, ...]

    def key(self, name: str) -> Key:
        """Return the key with this name."""
        return next(k for k in self.keys if k.name == name)

    @property
    def names(self) -> tuple[str, ...]:
        """The key names, in documentation order."""
        return tuple(k.name for k in self.keys)


_S, _I, _N, _M, _L, _SL, _C = (
    ValueKind.STRING,
    ValueKind.INTEGER,
    ValueKind.NUMBER,
    ValueKind.MAPPING,
    ValueKind.LIST,
    ValueKind.STRING_LIST,
    ValueKind.COUNTS,
)
SUBSCRIBER_TYPE = "ROS>accelerator"
PUBLISHER_TYPE = "accelerator>ROS"
BUS_WIDTHS = (8, 32, 64)
_DURATION = "clock cycles (an integer) or a duration with a unit: '10 us', '1.5 ms'"

# The sections below are rows of one table: alike in shape, each with keys of its own.
SCHEDULER = Section(
    "scheduler",
    "The scheduler sharing the PL→PS DMA channel among the publishers.",
    (
        Key(
            "algorithm",
            (_S,),
            "LRU, NPFP, PFP, ROEDF, LOEDF, LST, or auto (chosen by design-space exploration).",
            required=True,
            choices=SCHEDULER_ALGORITHMS,
        ),
    ),
)
MAXIMA = Section(
    "maxima",
    "The largest strings and sequences the logic accepts: they size its length counters and "
    "the publishers' buffers; a subscriber drops a message beyond them as malformed.",
    (
        Key("string", (_I,), "Most bytes of an unbounded string (default 4096)."),
        Key("sequence", (_I,), "Most elements of an unbounded sequence (default 1048576)."),
        Key("frame", (_I,), "Most bytes of a frame a store-and-forward publisher holds (65536)."),
        Key(
            "fields",
            (_C,),
            "Per field, by dotted path (data, transforms.header.frame_id; name[] for each "
            "string of a sequence of strings).",
        ),
    ),
)
PROJECT = Section(
    "project",
    "Project-wide settings.",
    (
        Key("name", (_S,), "Project name: a VHDL identifier.", required=True),
        Key("fpgaPart", (_S,), "Xilinx Zynq part; the family is derived from it."),
        Key("middleware", (_S,), "ROS (ROS 1) or ROS2 for every converter."),
        Key("distro", (_S,), "Type store: noetic for ROS 1; humble (default), jazzy... for ROS 2."),
        Key("busWidth", (_I,), "Bits of the DMA AXI-Streams.", choices=BUS_WIDTHS),
        Key("clockMHz", (_N,), "Clock of the programmable logic in MHz."),
        Key(
            "scheduler",
            (_S, _M),
            "The PL→PS scheduling algorithm, or a mapping with 'algorithm'.",
            section=SCHEDULER,
        ),
        Key(
            "msg_paths",
            (_S, _SL),
            "Directories of your own <package>/msg/*.msg, relative to the spec.",
        ),
        Key("maxima", (_M,), "Largest strings and sequences of the logic.", section=MAXIMA),
    ),
)
PORT = Section(
    "interface port",
    "A message port of an accelerator.",
    (
        Key("name", (_S,), "Port name (default: in0, in1... and out0, out1...)."),
        Key("middleware", (_S,), "Must agree with the project's middleware."),
        Key("message", (_S,), "Message type: pkg/Name or pkg/msg/Name.", required=True),
        Key("include", (_S, _SL), "Inputs: the only fields the accelerator needs."),
        Key("exclude", (_S, _SL), "Inputs: fields the accelerator does not need."),
    ),
)
INTERFACE = Section(
    "interface",
    "The accelerator's message ports.",
    (
        Key("input", (_L,), "Input ports.", section=PORT),
        Key("output", (_L,), "Output ports.", section=PORT),
    ),
)
ACCELERATOR = Section(
    "accelerator",
    "An accelerator type, instantiated by blocks whose type is its name.",
    (
        Key("name", (_S,), "Type name: a VHDL identifier.", required=True),
        Key(
            "type",
            (_S,),
            "How it is implemented.",
            required=True,
            choices=tuple(k.value for k in AcceleratorKind),
        ),
        Key("sources", (_S, _SL), "Source files, relative to the spec.", required=True),
        Key("interface", (_M,), "Its message ports.", required=True, section=INTERFACE),
        Key("top", (_S,), "Top-level function or entity (MyHDL: the @block function)."),
        Key("reference", (_S,), "Python reference model: 'file.py:function' or 'function'."),
    ),
)
# include/exclude are PORT's keys too (one FieldSelection in the IR); only their help differs:
# here what a connection carries, there what an accelerator input needs.
OUTGOING = Section(
    "outgoing",
    "A connection from this block to another.",
    (
        Key("name", (_S,), "The destination block.", required=True),
        Key("port", (_S,), "The destination's input port, when it has several."),
        Key("from", (_S,), "This block's output port, when it has several."),
        Key("include", (_S, _SL), "Carry only these fields (dotted paths, * wildcards)."),
        Key("exclude", (_S, _SL), "Do not carry these fields."),
    ),
)
BLOCK = Section(
    "block",
    "A component: a subscriber, a publisher, or an instance of an accelerator type.",
    (
        Key("name", (_S,), "Block name: a VHDL identifier.", required=True),
        Key(
            "type",
            (_S,),
            f"{SUBSCRIBER_TYPE}, {PUBLISHER_TYPE}, or the name of an accelerator type.",
            required=True,
        ),
        Key("middleware", (_S,), "Converters: must agree with the project's middleware."),
        Key(
            "mode",
            (_S,),
            "Converters: subscriber or publisher.",
            choices=("subscriber", "publisher"),
        ),
        Key("message", (_S,), "Converters: the message type.", required=False),
        Key("topic", (_S,), "Converters: the ROS topic (default: /<name>)."),
        Key("period", (_I, _S), f"Converters: time between messages, in {_DURATION}."),
        Key(
            "deadline",
            (_I, _S),
            f"Converters: relative deadline (default: the period), in {_DURATION}.",
        ),
        Key("maxBytes", (_I,), "Converters: largest frame in bytes (variable-size messages)."),
        Key("outgoing", (_L,), "Connections to other blocks.", section=OUTGOING),
    ),
)
ROOT = Section(
    "spec",
    "An rfc system specification.",
    (
        Key("project", (_M,), "Project-wide settings.", required=True, section=PROJECT),
        Key("accelerators", (_L,), "Accelerator types.", section=ACCELERATOR),
        Key(
            "blocks",
            (_L,),
            "The system's components and their connections.",
            required=True,
            section=BLOCK,
        ),
    ),
)


def json_schema() -> dict[str, Any]:
    """Render the format as a JSON Schema (draft 2020-12)."""
    schema = _section_schema(ROOT)
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "rfc system specification",
        **schema,
    }


def _section_schema(section: Section) -> dict[str, Any]:
    schema: dict[str, Any] = {
        "type": "object",
        "description": section.description,
        "properties": {key.name: _key_schema(key) for key in section.keys},
        "additionalProperties": False,
    }
    required = [key.name for key in section.keys if key.required]
    if required:
        schema["required"] = required
    return schema


def _key_schema(key: Key) -> dict[str, Any]:
    options = [_kind_schema(kind, key) for kind in key.kinds]
    schema = options[0] if len(options) == 1 else {"anyOf": options}
    return {"description": key.description, **schema}


def _kind_schema(kind: ValueKind, key: Key) -> dict[str, Any]:
    if kind is ValueKind.MAPPING:
        assert key.section is not None
        return _section_schema(key.section)
    if kind is ValueKind.LIST:
        assert key.section is not None
        return {"type": "array", "items": _section_schema(key.section)}
    if kind is ValueKind.STRING_LIST:
        return {"type": "array", "items": {"type": "string"}}
    if kind is ValueKind.COUNTS:
        return {"type": "object", "additionalProperties": {"type": "integer", "minimum": 0}}
    schema: dict[str, Any] = {
        ValueKind.STRING: {"type": "string"},
        ValueKind.INTEGER: {"type": "integer"},
        ValueKind.NUMBER: {"type": "number"},
        ValueKind.BOOLEAN: {"type": "boolean"},
    }[kind]
    choices = [c for c in key.choices if isinstance(c, str) == (kind is ValueKind.STRING)]
    if choices:
        schema = {**schema, "enum": choices}
    return schema


if __name__ == "__main__":
    print(json.dumps(json_schema(), indent=2, ensure_ascii=False))
