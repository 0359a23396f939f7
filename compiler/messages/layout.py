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

from rfc.messages.layout_model import (
    CDR_HEADER_SIZE,
    LENGTH_PREFIX_SIZE,
    FieldKind,
    Layout,
    LayoutField,
    format_path,
)
from rfc.messages.rosbags_adapter import PRIMITIVE_SIZES, FieldDef, MessageTypes, Middleware

__all__ = [  # the data model lives in rfc.messages.layout_model, which the runtime reads too
    "CDR_HEADER_SIZE",
    "LENGTH_PREFIX_SIZE",
    "FieldKind",
    "Layout",
    "LayoutField",
    "cdr_alignment",
    "flatten",
    "flatten_element",
    "format_path",
]


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
    layout: Layout = types.cache[key]
    return layout


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
        string_bound: int = 0,
        element: Layout | None = None,
    ) -> LayoutField:
        align = LENGTH_PREFIX_SIZE if self.cdr else 1
        offset = None
        if self.position is not None:
            offset = self._frame_offset(-(-self.position // align) * align)
            self.position = None
        return LayoutField(
            steps, ros_type, kind, element_type, align, offset, bound, string_bound, element
        )

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
    layout: Layout = types.cache[key]
    return layout
