"""The per-field ``maxima`` of a spec must name strings or sequences its converters carry.

A path that matches nothing would silently leave the default in place — the buffers and
counters the user meant to size would not change — so it is an error, with the closest paths.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from rfc.errors import RfcError, did_you_mean
from rfc.ir.infrastructure import Converter
from rfc.ir.model import BlockKind, Design
from rfc.messages.layout import FieldKind, Layout


def check_maxima(design: Design, converters: Iterable[Converter]) -> None:
    """Raise unless every per-field maximum names an unbounded string or sequence of the system.

    The system's messages are its converters' and its accelerators' ports (a message may travel
    between two accelerators only; those on the processor count too, as `rfc sim` holds their
    inputs to the maxima and C-simulated HLS accelerators are on the processor). A field bounded
    in its .msg keeps its bound, so a maximum for it would do nothing: it is not offered either.
    """
    layouts = [converter.layout for converter in converters]
    for block in design.blocks_of(BlockKind.ACCELERATOR):
        layouts += [port.layout for port in block.ports if port.layout is not None]
    paths = {path for layout in layouts for path in variable_paths(layout)}
    for path in design.project.maxima.fields:
        if path not in paths:
            raise RfcError(
                f"maxima give '{path}', which is not an unbounded string or sequence of the "
                "system's messages",
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
        if not leaf.bound:
            yield path
        if leaf.element is not None:
            yield from variable_paths(leaf.element, path + ".")
        elif (
            leaf.kind is not FieldKind.STRING
            and leaf.element_type == "string"
            and not (leaf.string_bound)
        ):
            yield path + "[]"
