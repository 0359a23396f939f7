"""Test helpers for field values: hypothesis strategies from a layout, and exact comparison."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from rfc.messages.layout import FieldKind, Layout, LayoutField
from rfc.messages.rosbags_adapter import PRIMITIVE_DTYPES

#: Sizes the strategies draw from: empty, short, and occasionally long.
SHORT = 6
LONG = 300


def _length(bound: int, long: int = LONG) -> st.SearchStrategy[int]:
    upper = bound or long
    return st.one_of(st.just(0), st.integers(0, min(SHORT, upper)), st.integers(0, upper))


def primitive(type_name: str) -> st.SearchStrategy[Any]:
    """Any value of a primitive, extremes, infinities and NaN included."""
    if type_name == "bool":
        return st.booleans()
    if type_name.startswith("float"):
        return st.floats(width=int(type_name[5:]))
    info = np.iinfo(PRIMITIVE_DTYPES[type_name])
    return st.integers(int(info.min), int(info.max))


def text(bound: int, long: int = LONG) -> st.SearchStrategy[str]:
    if bound:
        # A bound counts bytes on the wire: keep bounded strings ASCII.
        return _length(bound, long).flatmap(
            lambda n: st.text(st.characters(codec="ascii"), min_size=n, max_size=n)
        )
    return st.one_of(st.text(max_size=SHORT), st.text(min_size=long, max_size=long + 40))


def field_values(field: LayoutField, depth: int = 0, long: int = LONG) -> st.SearchStrategy[Any]:
    if field.kind is FieldKind.PRIMITIVE:
        return primitive(field.element_type)
    if field.kind is FieldKind.STRING:
        return text(field.bound, long)
    if field.element is not None:
        return st.lists(
            layout_values(field.element, depth + 1, long), max_size=field.bound or 3 - depth
        )
    if field.element_type == "string":
        return st.lists(text(field.string_bound, long), max_size=field.bound or SHORT)
    return hnp.arrays(
        PRIMITIVE_DTYPES[field.element_type],
        _length(field.bound, long),
        elements=primitive(field.element_type),
    )


def layout_values(
    layout: Layout, depth: int = 0, long: int = LONG
) -> st.SearchStrategy[dict[str, Any]]:
    """Flat values for every leaf of a layout; `long` is the size of long strings and arrays."""
    return st.fixed_dictionaries({f.path: field_values(f, depth, long) for f in layout.fields})


def same(a: Any, b: Any) -> bool:
    """Equality that treats NaN as equal to NaN, and arrays and lists element-wise."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype != b.dtype and a.size and b.size:
            return False
        floating = np.issubdtype(a.dtype, np.floating)
        return a.shape == b.shape and np.array_equal(a, b, equal_nan=floating)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b
