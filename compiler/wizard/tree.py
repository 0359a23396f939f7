"""A message type shown as the tree of its fields, for choosing what to pass on."""

from __future__ import annotations

from rfc.messages.rosbags_adapter import FieldDef, MessageTypes


def message_tree(types: MessageTypes, canonical: str) -> str:
    """Return the fields of `canonical` as an indented tree, one field per line.

    Each line holds the field's name and its type (``float64``, ``string``, ``Header``, with
    ``[n]`` for fixed arrays and ``[]`` for sequences), so dotted paths can be read off it.
    """
    lines = [types.display_name(canonical)]
    _add(types, canonical, "  ", lines)
    return "\n".join(lines)


def _add(types: MessageTypes, canonical: str, indent: str, lines: list[str]) -> None:
    for field in types.fields(canonical):
        lines.append(f"{indent}{field.name}: {_type_text(types, field)}")
        if field.is_message:
            _add(types, field.base, indent + "  ", lines)


def _type_text(types: MessageTypes, field: FieldDef) -> str:
    base = types.display_name(field.base) if field.is_message else field.base
    if field.array_length is not None:
        return f"{base}[{field.array_length}]"
    if field.is_sequence:
        return f"{base}[]"
    return base
