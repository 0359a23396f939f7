"""Frame sizes known at compile time: exact when static, otherwise an upper bound.

The scheduler's transfer time and a converter's largest accepted frame come from here. A
publisher whose selected fields are all fixed-size sends frames of one size even when the
message has strings or sequences: the unselected ones are sent empty (their defaults).
"""

from __future__ import annotations

from rfc.messages.codec import default_values, encode
from rfc.messages.layout import LENGTH_PREFIX_SIZE, FieldKind, Layout, LayoutField


def default_frame_bytes(layout: Layout) -> int:
    """Bytes of the frame whose every field holds its default (empty strings and sequences)."""
    return layout.fixed_size or len(encode(layout, default_values(layout)))


def frame_bound(layout: Layout) -> int | None:
    """An upper bound of the frame size, or None when a string or sequence is unbounded.

    Each field is counted with the most alignment padding it can need (CDR aligns to the
    field's size relative to the payload start, which is only known at run time).
    """
    if layout.fixed_size is not None:
        return layout.fixed_size
    total = layout.header_size
    for field in layout.fields:
        size = _field_bound(field, layout.is_cdr)
        if size is None:
            return None
        total += size
    return total


def _field_bound(field: LayoutField, cdr: bool) -> int | None:
    padding = field.align - 1
    if field.kind is FieldKind.PRIMITIVE:
        return padding + (field.element_size or 0)
    if field.bound == 0:
        return None
    if field.kind is FieldKind.STRING:
        return padding + LENGTH_PREFIX_SIZE + field.bound + (1 if cdr else 0)
    element = _element_bound(field, cdr)
    if element is None:
        return None
    size = field.element_size or 0  # primitives are contiguous: one padding, first element
    first = size - 1 if cdr and size else 0
    return padding + LENGTH_PREFIX_SIZE + first + field.bound * element


def _element_bound(field: LayoutField, cdr: bool) -> int | None:
    if field.element is not None:
        parts = [_field_bound(f, cdr) for f in field.element.fields]
        return None if None in parts else 7 + sum(p for p in parts if p is not None)
    if field.element_type == "string":
        if field.string_bound == 0:
            return None
        return 3 + LENGTH_PREFIX_SIZE + field.string_bound + (1 if cdr else 0)
    return field.element_size or 0
