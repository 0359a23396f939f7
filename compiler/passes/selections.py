"""Selections of a message type, computed once per distinct (type, selection) and kept.

Many connections of a system carry the same selection of the same type (a pipeline passes an
image on stage after stage); flattening and selecting rebuilds every leaf, so results are kept
in the cache of the `MessageTypes` they were derived from.
"""

from __future__ import annotations

from rfc.ir.fields import selected_paths, with_selection
from rfc.ir.model import FieldSelection
from rfc.messages.layout import Layout, flatten
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.messages.selection import select


def carried_fields(types: MessageTypes, message: str, selection: FieldSelection) -> tuple[str, ...]:
    """The leaf paths a selection picks from a message, in serialization order."""
    key = ("carried", message, selection)
    if key not in types.cache:
        layout = select(flatten(types, message), selection.include, selection.exclude)
        types.cache[key] = tuple(selected_paths(layout))
    paths: tuple[str, ...] = types.cache[key]
    return paths


def layout_selecting(types: MessageTypes, message: str, paths: frozenset[str]) -> Layout:
    """The layout of `message` with exactly `paths` selected."""
    key = ("selecting", message, paths)
    if key not in types.cache:
        types.cache[key] = with_selection(flatten(types, message), paths)
    layout: Layout = types.cache[key]
    return layout
