"""Frame sizes known at compile time: exact when static, otherwise an upper bound.

The scheduler's transfer time and a converter's largest accepted frame come from here. A
publisher whose selected fields are all fixed-size sends frames of one size even when the
message has strings or sequences: the unselected ones are sent empty (their defaults).
"""

from __future__ import annotations

from rfc.messages.codec import default_values, encode
from rfc.messages.layout import LENGTH_PREFIX_SIZE, FieldKind, Layout, LayoutField
from rfc.messages.limits import Limits


def default_frame_bytes(layout: Layout) -> int:
    """Bytes of the frame whose every field holds its default (empty strings and sequences)."""
    return layout.fixed_size or len(encode(layout, default_values(layout)))


def frame_bound(layout: Layout, maxima: Limits | None = None) -> int | None:
    """An upper bound of the frame size; None when a string or sequence is unbounded.

    Each field is counted with the most alignment padding it can need (CDR aligns to the
    field's size relative to the payload start, which is only known at run time). With
    `maxima`, an unbounded string or sequence counts at its maximum (what the logic accepts),
    so there is always a bound.
    """
    if layout.fixed_size is not None:
        return layout.fixed_size
    return _fields_bound(layout, maxima, "", header=layout.header_size)


def _fields_bound(
    layout: Layout, maxima: Limits | None, prefix: str, header: int = 0
) -> int | None:
    total = header
    for field in layout.fields:
        size = _field_bound(field, layout.is_cdr, maxima, prefix + field.path)
        if size is None:
            return None
        total += size
    return total


def _count(field: LayoutField, maxima: Limits | None, path: str) -> int | None:
    """Most characters or elements: the .msg bound, else the maximum, else unknown."""
    if field.bound:
        return field.bound
    return None if maxima is None else maxima.maximum(field, path)


def _field_bound(field: LayoutField, cdr: bool, maxima: Limits | None, path: str) -> int | None:
    padding = field.align - 1
    if field.kind is FieldKind.PRIMITIVE:
        return padding + (field.element_size or 0)
    count = _count(field, maxima, path)
    if count is None:
        return None
    if field.kind is FieldKind.STRING:
        return padding + LENGTH_PREFIX_SIZE + count + (1 if cdr else 0)
    element = _element_bound(field, cdr, maxima, path)
    if element is None:
        return None
    size = field.element_size or 0  # primitives are contiguous: one padding, first element
    first = size - 1 if cdr and size else 0
    return padding + LENGTH_PREFIX_SIZE + first + count * element


def _element_bound(field: LayoutField, cdr: bool, maxima: Limits | None, path: str) -> int | None:
    if field.element is not None:
        inner = _fields_bound(field.element, maxima, path + ".")
        return None if inner is None else 7 + inner
    if field.element_type == "string":
        if field.string_bound:
            longest = field.string_bound
        elif maxima is not None:
            longest = maxima.string_in_sequence(field, path)
        else:
            return None
        return 3 + LENGTH_PREFIX_SIZE + longest + (1 if cdr else 0)
    return field.element_size or 0
