"""The per-field ``maxima`` of a spec must name strings or sequences its converters carry.

A path that matches nothing would silently leave the default in place — the buffers and
counters the user meant to size would not change — so it is an error, with the closest paths.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from rfc.errors import RfcError, did_you_mean
from rfc.ir.infrastructure import Converter
from rfc.ir.model import Design
from rfc.messages.layout import FieldKind, Layout


def check_maxima(design: Design, converters: Iterable[Converter]) -> None:
    """Raise unless every per-field maximum names a string or sequence of some converter."""
    paths = {path for converter in converters for path in variable_paths(converter.layout)}
    for path in design.project.maxima.fields:
        if path not in paths:
            raise RfcError(
                f"maxima give '{path}', which is not a string or sequence of the system's messages",
                location=design.project.spots.get(f"maxima.fields.{path}", design.project.location),
                hint=did_you_mean(path, sorted(paths))
                or "write the dotted path of a string or sequence (rfc msg show TYPE lists them)",
            )


def variable_paths(layout: Layout, prefix: str = "") -> Iterator[str]:
    """The paths `rfc.messages.limits.Limits.fields` keys, as the converters' plans use them.

    Strings and sequences; nested ones through their sequence (``transforms.header.frame_id``);
    ``name[]`` for the strings of a sequence of strings.
    """
    for leaf in layout.fields:
        if leaf.kind is FieldKind.PRIMITIVE:
            continue
        path = prefix + leaf.path
        yield path
        if leaf.element is not None:
            yield from variable_paths(leaf.element, path + ".")
        elif leaf.kind is not FieldKind.STRING and leaf.element_type == "string":
            yield path + "[]"
