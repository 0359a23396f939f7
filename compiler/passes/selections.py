"""Selections of a message type, computed once per distinct (type, selection) and kept.

Many connections of a system carry the same selection of the same type (a pipeline passes an
image on stage after stage); flattening and selecting rebuilds every leaf, so results are kept
in the cache of the `MessageTypes` they were derived from.
"""

from __future__ import annotations

from rfc.ir.fields import selected_paths, with_selection
from rfc.messages.layout import Layout, flatten
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.messages.selection import select


def carried_fields(
    types: MessageTypes, message: str, include: tuple[str, ...], exclude: tuple[str, ...]
) -> tuple[str, ...]:
    """The leaf paths that include/exclude patterns select, in serialization order."""
    key = ("carried", message, include, exclude)
    if key not in types.cache:
        types.cache[key] = tuple(selected_paths(select(flatten(types, message), include, exclude)))
    paths: tuple[str, ...] = types.cache[key]
    return paths


def layout_selecting(types: MessageTypes, message: str, paths: frozenset[str]) -> Layout:
    """The layout of `message` with exactly `paths` selected."""
    key = ("selecting", message, paths)
    if key not in types.cache:
        types.cache[key] = with_selection(flatten(types, message), paths)
    layout: Layout = types.cache[key]
    return layout
