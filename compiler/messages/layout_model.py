"""The byte layout of a message as data: what the runtime needs to check and shape frames.

A `Layout` is the flattened form of a message type (``rfc.messages.layout.flatten`` derives it
from the definitions at build time): its leaves in serialization order, with their kinds,
alignment and static offsets. The runtime plan carries layouts as JSON (`layout_to_json`,
`layout_from_json`), so the processor side decodes and shapes frames with NumPy alone.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import StrEnum
from functools import cached_property
from typing import Any

import numpy as np


class Middleware(StrEnum):
    """The robotics middleware whose wire format a converter speaks."""

    ROS1 = "ros1"
    ROS2 = "ros2"

    @property
    def label(self) -> str:
        """The name people write: ``ROS 1``, ``ROS 2``."""
        return f"ROS {self.value[-1]}"


#: Serialized size in bytes of each primitive type rosbags knows how to serialize.
PRIMITIVE_SIZES = {
    "bool": 1,
    "byte": 1,
    "char": 1,
    "int8": 1,
    "uint8": 1,
    "int16": 2,
    "uint16": 2,
    "int32": 4,
    "uint32": 4,
    "int64": 8,
    "uint64": 8,
    "float32": 4,
    "float64": 8,
}

#: NumPy dtype of each primitive, as rosbags stores arrays of it (byte is signed, char unsigned).
PRIMITIVE_DTYPES = {
    "bool": np.dtype(np.bool_),
    "byte": np.dtype(np.int8),
    "char": np.dtype(np.uint8),
    "int8": np.dtype(np.int8),
    "uint8": np.dtype(np.uint8),
    "int16": np.dtype("<i2"),
    "uint16": np.dtype("<u2"),
    "int32": np.dtype("<i4"),
    "uint32": np.dtype("<u4"),
    "int64": np.dtype("<i8"),
    "uint64": np.dtype("<u8"),
    "float32": np.dtype("<f4"),
    "float64": np.dtype("<f8"),
}

#: Bytes of the CDR encapsulation header in front of every ROS 2 payload.
CDR_HEADER_SIZE = 4
#: Size and alignment of the uint32 that prefixes strings and sequences.
LENGTH_PREFIX_SIZE = 4


# An enum then a record, like the converters' SlotRole, the node's Device, in shape only.
class FieldKind(StrEnum):
    """How a leaf field is serialized."""

    PRIMITIVE = "primitive"
    """A fixed-size scalar at its (aligned) position."""
    STRING = "string"
    """uint32 byte count, then the bytes (CDR: the count includes a trailing NUL)."""
    SEQUENCE = "sequence"
    """uint32 element count, then the elements: primitives, strings or messages."""


@dataclass(frozen=True)
class LayoutField:
    """One leaf of a flattened message.

    Attributes:
        steps: The path as field names and fixed-array indices: ``("pose", "covariance", 35)``.
        ros_type: ROS type as users write it: ``float64``, ``string``, ``float32[]``,
            ``geometry_msgs/msg/Point[]``.
        kind: How the field is serialized.
        element_type: Primitive name, ``string``, or message type of one value or element.
        align: Alignment in bytes of the field's first serialized item (the value, or the length
            prefix of a string or sequence), relative to the payload start; 1 for ROS 1.
        offset: Bytes from the first byte of the frame, or None when it depends on run-time
            lengths.
        bound: Maximum length of a bounded string or sequence, 0 when unbounded.
        string_bound: For a sequence of strings, the bound of each string.
        element: Layout of one element of a sequence of messages.
        selected: Whether the accelerator uses the field (see `rfc.messages.selection`).
    """

    steps: tuple[str | int, ...]
    ros_type: str
    kind: FieldKind
    element_type: str
    align: int
    offset: int | None
    bound: int = 0
    string_bound: int = 0
    element: Layout | None = None
    selected: bool = True

    @cached_property
    def path(self) -> str:
        """Dotted path with fixed-array indices: ``pose.covariance[35]`` (computed once)."""
        return format_path(self.steps)

    @property
    def element_size(self) -> int | None:
        """Serialized bytes of one value or element; None for strings and messages."""
        return PRIMITIVE_SIZES.get(self.element_type)

    @property
    def bits(self) -> int | None:
        """Width of one value in bits (a string's characters count as 8); None for messages."""
        if self.element_type == "string":
            return 8
        size = self.element_size
        return None if size is None else 8 * size

    @property
    def is_dynamic(self) -> bool:
        """Whether the field's serialized length is only known at run time."""
        return self.kind is not FieldKind.PRIMITIVE


@dataclass(frozen=True)
class Layout:
    """The flattened layout of one message type for one middleware.

    Attributes:
        type_name: Canonical type name (``pkg/msg/Name``).
        display_name: The name as the middleware spells it.
        middleware: ROS 1 or ROS 2: decides the header, alignment and string encoding.
        fields: Leaves in serialization order.
        fixed_size: Bytes of the whole frame when no field is variable-length, else None.
            Element layouts (inside a sequence) have no frame and report None.
        is_element: Whether this is the layout of a sequence element rather than a frame.
    """

    type_name: str
    display_name: str
    middleware: Middleware
    fields: tuple[LayoutField, ...]
    fixed_size: int | None
    is_element: bool = False

    @property
    def header_size(self) -> int:
        """Bytes before the first field: the CDR header for ROS 2 frames, else none."""
        if self.is_element or self.middleware is Middleware.ROS1:
            return 0
        return CDR_HEADER_SIZE

    @property
    def is_cdr(self) -> bool:
        """Whether primitives are aligned to their size (ROS 2's CDR)."""
        return self.middleware is Middleware.ROS2

    def field(self, path: str) -> LayoutField:
        """Return the leaf with this exact path."""
        for field in self.fields:
            if field.path == path:
                return field
        raise KeyError(path)

    def selected_fields(self) -> tuple[LayoutField, ...]:
        """Return the leaves the accelerator uses."""
        return tuple(f for f in self.fields if f.selected)

    def with_fields(self, fields: tuple[LayoutField, ...]) -> Layout:
        """Return a copy with other leaves (same types and offsets, new selection)."""
        return replace(self, fields=fields)


def format_path(steps: tuple[str | int, ...]) -> str:
    """Render path steps: names joined by dots, array indices in brackets."""
    text = ""
    for step in steps:
        if isinstance(step, int):
            text += f"[{step}]"
        else:
            text += f".{step}" if text else step
    return text


def layout_to_json(layout: Layout) -> dict[str, Any]:
    """A JSON-ready document of a layout (selection, bounds and nested element layouts)."""
    return {
        "type": layout.type_name,
        "display": layout.display_name,
        "middleware": layout.middleware.value,
        "fixed_size": layout.fixed_size,
        "element": layout.is_element,
        "fields": [
            {
                "steps": list(f.steps),
                "ros_type": f.ros_type,
                "kind": f.kind.value,
                "element_type": f.element_type,
                "align": f.align,
                "offset": f.offset,
                "bound": f.bound,
                "string_bound": f.string_bound,
                "element": None if f.element is None else layout_to_json(f.element),
                "selected": f.selected,
            }
            for f in layout.fields
        ],
    }


def layout_from_json(document: dict[str, Any]) -> Layout:
    """The layout `layout_to_json` wrote."""
    fields = tuple(
        LayoutField(
            tuple(f["steps"]),
            f["ros_type"],
            FieldKind(f["kind"]),
            f["element_type"],
            f["align"],
            f["offset"],
            f["bound"],
            f["string_bound"],
            None if f["element"] is None else layout_from_json(f["element"]),
            f["selected"],
        )
        for f in document["fields"]
    )
    return Layout(
        document["type"],
        document["display"],
        Middleware(document["middleware"]),
        fields,
        document["fixed_size"],
        document["element"],
    )
