"""The reference codec: field values ↔ frame bytes, driven by nothing but a `Layout`.

This is the executable specification of the generated converters. It walks the flattened
fields in order, as the hardware does, aligning CDR primitives relative to the payload start.
rosbags is its oracle: for every type, `encode` must reproduce rosbags' serialization byte for
byte and `decode` must agree with rosbags' deserialization.

Values are flat, keyed by leaf path: scalars as Python numbers, strings as `str`, sequences of
primitives as NumPy arrays, sequences of strings as lists, and sequences of messages as lists of
flat dicts keyed by the element's own paths.
"""

from __future__ import annotations

import struct
from collections.abc import Mapping
from typing import Any

import numpy as np

from rfc.messages.layout_model import (
    LENGTH_PREFIX_SIZE,
    PRIMITIVE_DTYPES,
    FieldKind,
    Layout,
    LayoutField,
)

#: The CDR encapsulation header rfc writes: plain CDR, little-endian, no options.
CDR_LITTLE_ENDIAN = b"\x00\x01\x00\x00"

#: Little-endian packing of each ROS primitive (one element).
PRIMITIVE_STRUCTS = {
    name: struct.Struct("<" + code)
    for name, code in {
        "bool": "?",
        "byte": "b",
        "char": "B",
        "int8": "b",
        "uint8": "B",
        "int16": "h",
        "uint16": "H",
        "int32": "i",
        "uint32": "I",
        "int64": "q",
        "uint64": "Q",
        "float32": "f",
        "float64": "d",
    }.items()
}
_LENGTH = PRIMITIVE_STRUCTS["uint32"]

Values = dict[str, Any]


class FrameError(ValueError):
    """Bytes that are not a valid frame of the layout; `reason` is a short stable code."""

    def __init__(self, reason: str, detail: str) -> None:
        super().__init__(f"{reason}: {detail}")
        self.reason = reason


def encode(layout: Layout, values: Mapping[str, Any]) -> bytes:
    """Serialize flat field values into a frame (ROS 2: with the CDR header).

    Args:
        layout: The message's layout.
        values: A value for every leaf path of the layout.

    Returns:
        The frame, byte-exact with rosbags' serialization.
    """
    out = bytearray(CDR_LITTLE_ENDIAN if layout.header_size else b"")
    _encode_fields(layout, values, out, layout.header_size)
    return bytes(out)


def _encode_fields(layout: Layout, values: Mapping[str, Any], out: bytearray, base: int) -> None:
    cdr = layout.is_cdr
    for field in layout.fields:
        value = values[field.path]
        if field.kind is FieldKind.PRIMITIVE:
            _pad(out, base, field.align)
            out += PRIMITIVE_STRUCTS[field.element_type].pack(value)
        elif field.kind is FieldKind.STRING:
            _encode_string(value, out, base, cdr)
        else:
            _pad(out, base, field.align)
            out += _LENGTH.pack(len(value))
            _encode_elements(field, value, out, base, cdr)


def _encode_elements(
    field: LayoutField, elements: Any, out: bytearray, base: int, cdr: bool
) -> None:
    if field.element is not None:
        for element in elements:
            _encode_fields(field.element, element, out, base)
    elif field.element_type == "string":
        for text in elements:
            _encode_string(text, out, base, cdr)
    elif len(elements):
        size = field.element_size or 1
        _pad(out, base, min(size, 8) if cdr else 1)
        out += np.asarray(elements, dtype=PRIMITIVE_DTYPES[field.element_type]).tobytes()


def _encode_string(text: str, out: bytearray, base: int, cdr: bool) -> None:
    data = text.encode()
    if cdr:
        _pad(out, base, LENGTH_PREFIX_SIZE)
        out += _LENGTH.pack(len(data) + 1) + data + b"\x00"
    else:
        out += _LENGTH.pack(len(data)) + data


def _pad(out: bytearray, base: int, align: int) -> None:
    out += bytes(-(len(out) - base) % align)


def decode(layout: Layout, frame: bytes | memoryview) -> Values:
    """Parse a frame into flat field values.

    A ROS 2 frame may end with up to 3 padding bytes that round it to a multiple of 4, as DDS
    middlewares write them; their values are ignored, as are those of alignment padding.

    Raises:
        FrameError: The frame is truncated, too long, big-endian, or holds a malformed string.
    """
    data = memoryview(frame).cast("B")
    base = layout.header_size
    if base:
        if len(data) < base:
            raise FrameError("truncated", f"{len(data)} bytes cannot hold the CDR header")
        if bytes(data[:2]) != CDR_LITTLE_ENDIAN[:2]:
            raise FrameError("encapsulation", f"CDR header {bytes(data[:2]).hex()} is not 0001")
    reader = _Reader(data, base, layout.is_cdr)
    values = reader.fields(layout)
    allowed = reader.pos + (-reader.pos % 4 if base else 0)
    if len(data) > allowed:
        raise FrameError(
            "trailing", f"{len(data) - reader.pos} bytes after the last field of {layout.type_name}"
        )
    return values


class _Reader:
    """A cursor over a frame that aligns and bounds-checks as it goes."""

    def __init__(self, data: memoryview, base: int, cdr: bool) -> None:
        self.data = data
        self.base = base
        self.cdr = cdr
        self.pos = base

    def take(self, count: int, align: int) -> memoryview:
        self.pos += -(self.pos - self.base) % align
        end = self.pos + count
        if count < 0 or end > len(self.data):
            raise FrameError("truncated", f"needs {end} bytes but the frame has {len(self.data)}")
        chunk = self.data[self.pos : end]
        self.pos = end
        return chunk

    def count(self, field: LayoutField) -> int:
        length: int = _LENGTH.unpack(self.take(LENGTH_PREFIX_SIZE, field.align))[0]
        if field.bound and length > field.bound:
            raise FrameError("bound", f"{field.path} holds {length} items, bound {field.bound}")
        return length

    def fields(self, layout: Layout) -> Values:
        values: Values = {}
        for field in layout.fields:
            if field.kind is FieldKind.PRIMITIVE:
                codec = PRIMITIVE_STRUCTS[field.element_type]
                (values[field.path],) = codec.unpack(self.take(codec.size, field.align))
            elif field.kind is FieldKind.STRING:
                values[field.path] = self.string(field.path, field.bound)
            else:
                values[field.path] = self.elements(field, self.count(field))
        return values

    def elements(self, field: LayoutField, count: int) -> Any:
        if field.element is not None:
            return [self.fields(field.element) for _ in range(count)]
        if field.element_type == "string":
            return [self.string(field.path, field.string_bound) for _ in range(count)]
        size = field.element_size or 1
        if count == 0:
            return np.zeros(0, dtype=PRIMITIVE_DTYPES[field.element_type])
        raw = self.take(count * size, min(size, 8) if self.cdr else 1)
        return np.frombuffer(raw, dtype=PRIMITIVE_DTYPES[field.element_type]).copy()

    def string(self, path: str, bound: int) -> str:
        (length,) = _LENGTH.unpack(self.take(LENGTH_PREFIX_SIZE, 4 if self.cdr else 1))
        raw = bytes(self.take(length, 1))
        if self.cdr:
            if not raw or raw[-1] != 0:
                raise FrameError("string", f"{path} is not NUL-terminated")
            raw = raw[:-1]
        if bound and len(raw) > bound:
            raise FrameError("bound", f"{path} holds {len(raw)} bytes, bound {bound}")
        try:
            return raw.decode()
        except UnicodeDecodeError as exc:
            raise FrameError("string", f"{path} is not UTF-8: {exc}") from None


def default_values(layout: Layout) -> Values:
    """Return the value a publisher sends for fields nobody drives: zero, false, empty."""
    values: Values = {}
    for field in layout.fields:
        if field.kind is FieldKind.STRING:
            values[field.path] = ""
        elif field.kind is FieldKind.SEQUENCE:
            empty = field.element is not None or field.element_type == "string"
            values[field.path] = [] if empty else np.zeros(0, PRIMITIVE_DTYPES[field.element_type])
        else:
            values[field.path] = PRIMITIVE_DTYPES[field.element_type].type(0).item()
    return values
