"""Conversions between rosbags message objects and the codec's flat field values.

The flat form is what converters and accelerators see (one value per leaf path); message
objects are what rosbags (and ROS code) uses. Tests use both directions to hold the codec to
rosbags, and the runtime uses them to hand messages to software accelerators.
"""

from __future__ import annotations

from collections.abc import Mapping
from itertools import pairwise
from typing import Any

import numpy as np

from rfc.messages.codec import Values
from rfc.messages.layout import FieldKind, Layout, LayoutField
from rfc.messages.rosbags_adapter import PRIMITIVE_DTYPES, MessageTypes, attribute_name


def message_to_values(message: object, layout: Layout) -> Values:
    """Read every leaf of a message object into flat values."""
    values: Values = {}
    for field in layout.fields:
        value: Any = message
        for step in field.steps:
            value = value[step] if isinstance(step, int) else getattr(value, attribute_name(step))
        values[field.path] = _leaf_value(field, value)
    return values


def _leaf_value(field: LayoutField, value: Any) -> Any:
    if field.kind is FieldKind.PRIMITIVE:
        return value.item() if isinstance(value, np.generic) else value
    if field.kind is FieldKind.STRING:
        return value
    if field.element is not None:
        return [message_to_values(item, field.element) for item in value]
    if field.element_type == "string":
        return list(value)
    return np.asarray(value, dtype=PRIMITIVE_DTYPES[field.element_type])


def values_to_message(values: Mapping[str, Any], layout: Layout, types: MessageTypes) -> object:
    """Build a rosbags message object from flat values."""
    return types.build(layout.type_name, values_to_tree(values, layout))


def values_to_tree(values: Mapping[str, Any], layout: Layout) -> dict[str, Any]:
    """Nest flat values into a dict of field name → value (sub-messages as dicts)."""
    tree: dict[str, Any] = {}
    for field in layout.fields:
        value = values[field.path]
        if field.element is not None:
            value = [values_to_tree(item, field.element) for item in value]
        node: Any = tree
        steps = field.steps
        for step, following in pairwise(steps):
            node = _child(node, step, following)
        _assign(node, steps[-1], value)
    return tree


def _child(node: Any, step: str | int, following: str | int) -> Any:
    """Return the container at `step`, creating a dict (next step a name) or list (an index)."""
    empty: Any = [] if isinstance(following, int) else {}
    if isinstance(step, int):
        while len(node) <= step:
            node.append(None)
        if node[step] is None:
            node[step] = empty
        return node[step]
    return node.setdefault(step, empty)


def _assign(node: Any, step: str | int, value: Any) -> None:
    if isinstance(step, int):
        while len(node) <= step:
            node.append(None)
    node[step] = value
