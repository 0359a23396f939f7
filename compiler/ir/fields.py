"""Leaf paths of a layout: which are selected, and marking a given set as selected.

A leaf inside the elements of a sequence of messages is addressed through the sequence
(``transforms.header.frame_id``), as `rfc.messages.selection` spells it.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace

from rfc.messages.layout import Layout


def selected_paths(layout: Layout, prefix: str = "") -> Iterator[str]:
    """Yield the selected leaf paths in serialization order."""
    for field in layout.fields:
        path = prefix + field.path
        if field.element is not None:
            yield from selected_paths(field.element, path + ".")
        elif field.selected:
            yield path


def with_selection(layout: Layout, paths: frozenset[str], prefix: str = "") -> Layout:
    """Return the layout with exactly the leaves in `paths` selected."""
    fields = []
    for field in layout.fields:
        path = prefix + field.path
        if field.element is not None:
            element = with_selection(field.element, paths, path + ".")
            chosen = any(f.selected for f in element.fields)
            fields.append(replace(field, element=element, selected=chosen))
        else:
            fields.append(replace(field, selected=path in paths))
    return layout.with_fields(tuple(fields))
