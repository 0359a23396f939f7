"""Configured maxima: how long a string or sequence the generated hardware accepts.

ROS strings and sequences are unbounded unless the .msg gives a bound, but hardware counters,
FIFOs and frame buffers need a size. A `Limits` gives the defaults and per-field overrides; a
bounded field always uses its own bound. A subscriber flags a message whose length exceeds the
maximum as malformed, drops it and resynchronizes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from rfc.errors import RfcError
from rfc.messages.layout_model import FieldKind, Layout, LayoutField

#: Largest length a ROS length prefix (uint32) can carry.
MAX_LENGTH = 2**32 - 1


@dataclass(frozen=True)
class Limits:
    """Maxima for unbounded strings and sequences, and the publisher's frame buffer.

    Attributes:
        string: Most characters (bytes, without CDR's terminator) of an unbounded string.
        sequence: Most elements of an unbounded sequence.
        frame: Most bytes of one frame a store-and-forward publisher buffers (see
            `rfc.lib.converters.plan.Plan.store_and_forward`).
        fields: Per-field maxima by path, overriding `string` and `sequence`; paths inside the
            elements of a sequence of messages go through the sequence
            (``transforms.header.frame_id``); the strings of a sequence of strings are keyed
            by its path and ``[]`` (``name[]``).
    """

    string: int = 4096
    sequence: int = 2**20
    frame: int = 65536
    fields: Mapping[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name, value in (("string", self.string), ("sequence", self.sequence)):
            _check(name, value)
        if not 1 <= self.frame <= MAX_LENGTH:
            raise RfcError(f"frame buffer of {self.frame} bytes is not between 1 and {MAX_LENGTH}")
        for path, value in self.fields.items():
            _check(f"maximum of '{path}'", value)
        object.__setattr__(self, "fields", MappingProxyType(dict(self.fields)))

    def maximum(self, field: LayoutField, path: str) -> int:
        """Return the most characters or elements the field may hold.

        Args:
            field: A string or sequence leaf.
            path: Its full path (through enclosing sequences), as `fields` keys it.
        """
        if field.bound:
            return field.bound
        if path in self.fields:
            return self.fields[path]
        return self.string if field.kind is FieldKind.STRING else self.sequence

    def string_in_sequence(self, field: LayoutField, path: str) -> int:
        """Return the most bytes of each string of a sequence of strings (keyed ``path[]``)."""
        if field.string_bound:
            return field.string_bound
        return self.fields.get(path + "[]", self.string)

    def beyond(self, layout: Layout, values: Mapping[str, Any], prefix: str = "") -> str | None:
        """The path of the first string or sequence longer than its maximum, if any.

        Args:
            layout: The message (or sequence element) the values are of.
            values: Its decoded values (`rfc.messages.codec.decode`).
            prefix: The path of the enclosing sequence and a dot, inside its elements.
        """
        for leaf in layout.fields:
            if leaf.kind is FieldKind.PRIMITIVE:
                continue
            path, value = prefix + leaf.path, values[leaf.path]
            if _size(value) > self.maximum(leaf, path):
                return path
            if leaf.element is not None:
                for element in value:
                    if (found := self.beyond(leaf.element, element, path + ".")) is not None:
                        return found
            elif leaf.kind is not FieldKind.STRING and leaf.element_type == "string":
                longest = max((_size(text) for text in value), default=0)
                if longest > self.string_in_sequence(leaf, path):
                    return path + "[]"
        return None


def _size(value: Any) -> int:
    """Bytes of a string (UTF-8, as on the wire), elements of a sequence."""
    return len(value.encode()) if isinstance(value, str) else len(value)


def _check(name: str, value: int) -> None:
    if not 0 <= value < MAX_LENGTH:
        raise RfcError(f"{name} {value} is not between 0 and {MAX_LENGTH - 1}")


def limits_to_json(limits: Limits) -> dict[str, Any]:
    """A JSON-ready document of the maxima (for the runtime plan)."""
    return {
        "string": limits.string,
        "sequence": limits.sequence,
        "frame": limits.frame,
        "fields": dict(limits.fields),
    }


def limits_from_json(document: dict[str, Any]) -> Limits:
    """The maxima `limits_to_json` wrote."""
    return Limits(document["string"], document["sequence"], document["frame"], document["fields"])
