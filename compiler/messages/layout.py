"""Flattening: a message type becomes the ordered list of its leaf fields with their byte layout.

This is the data-type analysis every generated component implements (the paper's §3 and §5.2):
nested messages are inlined and fixed-size arrays unrolled, so what remains is a flat sequence
of primitives, strings and sequences. Offsets count from the first byte of the serialized frame,
which for ROS 2 is the 4-byte CDR encapsulation header. An offset is static until the first
variable-length field; after it, the hardware tracks the position (and, for CDR, the position
modulo 8 for alignment) at run time.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace
from enum import StrEnum
from functools import cached_property

from rfc.messages.rosbags_adapter import PRIMITIVE_SIZES, FieldDef, MessageTypes, Middleware

#: Bytes of the CDR encapsulation header in front of every ROS 2 payload.
CDR_HEADER_SIZE = 4
#: Size and alignment of the uint32 that prefixes strings and sequences.
LENGTH_PREFIX_SIZE = 4


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


def cdr_alignment(size: int) -> int:
    """CDR aligns a primitive to its own size, at most 8 bytes."""
    return min(size, 8)


def flatten(types: MessageTypes, type_name: str) -> Layout:
    """Flatten a message type into its frame layout (cached with `types`).

    Args:
        types: The definitions to use; they also decide the middleware.
        type_name: Any usual spelling of the type.

    Returns:
        The layout, every leaf selected.

    Raises:
        RfcError: The type is unknown (with the closest names suggested).
    """
    canonical = types.resolve(type_name)
    key = ("layout", canonical)
    if key not in types.cache:
        types.cache[key] = _Flattener(types).layout(canonical, is_element=False)
    return types.cache[key]


class _Flattener:
    """Walks the definitions depth first, tracking the static byte position while it lasts."""

    def __init__(self, types: MessageTypes) -> None:
        self.types = types
        self.cdr = types.middleware is Middleware.ROS2

    def layout(self, canonical: str, *, is_element: bool) -> Layout:
        header = 0 if is_element or not self.cdr else CDR_HEADER_SIZE
        # Element positions depend on where the element starts: all dynamic.
        self.position: int | None = None if is_element else 0
        fields = tuple(self._fields(canonical, ()))
        fixed_size = None if is_element or self.position is None else header + self.position
        return Layout(
            canonical,
            self.types.display_name(canonical),
            self.types.middleware,
            fields,
            fixed_size,
            is_element,
        )

    def _fields(self, canonical: str, prefix: tuple[str | int, ...]) -> Iterator[LayoutField]:
        for definition in self.types.fields(canonical):
            steps = (*prefix, definition.name)
            if definition.array_length is None:
                yield from self._leaves(definition, steps)
            else:
                for index in range(definition.array_length):
                    yield from self._leaves(definition, (*steps, index))

    def _leaves(self, definition: FieldDef, steps: tuple[str | int, ...]) -> Iterator[LayoutField]:
        if definition.is_sequence:
            yield self._sequence(definition, steps)
        elif definition.is_message:
            yield from self._fields(definition.base, steps)
        elif definition.base == "string":
            yield self._variable(
                steps, "string", FieldKind.STRING, "string", definition.string_bound
            )
        else:
            yield self._primitive(steps, definition.base)

    def _primitive(self, steps: tuple[str | int, ...], base: str) -> LayoutField:
        size = PRIMITIVE_SIZES[base]
        align = cdr_alignment(size) if self.cdr else 1
        offset = None
        if self.position is not None:
            self.position = -(-self.position // align) * align
            offset = self._frame_offset(self.position)
            self.position += size
        return LayoutField(steps, base, FieldKind.PRIMITIVE, base, align, offset)

    def _variable(
        self,
        steps: tuple[str | int, ...],
        ros_type: str,
        kind: FieldKind,
        element_type: str,
        bound: int,
        **extra: object,
    ) -> LayoutField:
        align = LENGTH_PREFIX_SIZE if self.cdr else 1
        offset = None
        if self.position is not None:
            offset = self._frame_offset(-(-self.position // align) * align)
            self.position = None
        return LayoutField(steps, ros_type, kind, element_type, align, offset, bound, **extra)

    def _sequence(self, definition: FieldDef, steps: tuple[str | int, ...]) -> LayoutField:
        element = None
        if definition.is_message:
            element = flatten_element(self.types, definition.base)
            ros_type = f"{self.types.display_name(definition.base)}[]"
        else:
            ros_type = f"{definition.base}[]"
        return self._variable(
            steps,
            ros_type,
            FieldKind.SEQUENCE,
            definition.base,
            definition.sequence_bound,
            string_bound=definition.string_bound,
            element=element,
        )

    def _frame_offset(self, position: int) -> int:
        return position + (CDR_HEADER_SIZE if self.cdr else 0)


def flatten_element(types: MessageTypes, canonical: str) -> Layout:
    """Flatten a message type as the element of a sequence: every offset is dynamic."""
    key = ("element", canonical)
    if key not in types.cache:
        types.cache[key] = _Flattener(types).layout(canonical, is_element=True)
    return types.cache[key]
