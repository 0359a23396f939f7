"""Field selections: which leaves of a message an accelerator uses (the paper's include/exclude).

A pattern is a dotted path, optionally with wildcards: ``header.stamp``, ``data``,
``header.*``, ``pose.covariance[*]``. A ``*`` matches within one path segment; a pattern that
names a sub-message or an array selects every leaf under it. Leaves inside the elements of a
sequence of messages are addressed through the sequence: ``transforms.header.frame_id`` (the
spelling ``transforms[].header.frame_id`` is accepted too); such a sequence is selected when any
of its element leaves is.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence
from dataclasses import replace

from rfc.errors import RfcError, SourceLocation, did_you_mean
from rfc.messages.layout import Layout, LayoutField


def select(layout: Layout, include: Sequence[str] = (), exclude: Sequence[str] = ()) -> Layout:
    """Return the layout with `selected` set on every leaf.

    A leaf is selected when it matches an include pattern (or there are none) and no exclude
    pattern.

    Raises:
        RfcError: A pattern matches no field; the message suggests the closest paths.
    """
    for pattern in (*include, *exclude):
        validate_pattern(layout, pattern)
    return _select(layout, _compile(include), _compile(exclude), "")


def validate_pattern(layout: Layout, pattern: str, location: SourceLocation | None = None) -> None:
    """Check that a pattern matches at least one leaf of the layout.

    Raises:
        RfcError: It matches none; the hint names the closest valid paths.
    """
    regex = _compile([pattern])[0]
    if any(regex.match(path) for path in leaf_paths(layout)):
        return
    raise RfcError(
        f"{layout.display_name} has no field '{pattern}'",
        location=location,
        hint=did_you_mean(_normalize(pattern), sorted(all_paths(layout)))
        or f"its top-level fields are {', '.join(_top_level(layout))}",
    )


def leaf_paths(layout: Layout, prefix: str = "") -> Iterator[str]:
    """Yield every selectable leaf path, descending into elements of message sequences."""
    for field in layout.fields:
        path = prefix + field.path
        if field.element is not None:
            yield from leaf_paths(field.element, path + ".")
        else:
            yield path


def all_paths(layout: Layout) -> set[str]:
    """Return every valid pattern without wildcards: leaves and the sub-messages above them."""
    paths: set[str] = set()
    for leaf in leaf_paths(layout):
        parts = re.split(r"(?=[.\[])", leaf)
        paths.update("".join(parts[: i + 1]) for i in range(len(parts)))
    return paths


def _top_level(layout: Layout) -> list[str]:
    return list(dict.fromkeys(str(field.steps[0]) for field in layout.fields))


def _select(
    layout: Layout, include: list[re.Pattern[str]], exclude: list[re.Pattern[str]], prefix: str
) -> Layout:
    fields: list[LayoutField] = []
    for field in layout.fields:
        path = prefix + field.path
        if field.element is not None:
            element = _select(field.element, include, exclude, path + ".")
            chosen = any(f.selected for f in element.fields)
            fields.append(replace(field, element=element, selected=chosen))
        else:
            chosen = (not include or any(p.match(path) for p in include)) and not any(
                p.match(path) for p in exclude
            )
            fields.append(replace(field, selected=chosen))
    return layout.with_fields(tuple(fields))


def _normalize(pattern: str) -> str:
    return pattern.strip().replace("[]", "")


def _compile(patterns: Sequence[str]) -> list[re.Pattern[str]]:
    compiled = []
    for pattern in patterns:
        body = re.escape(_normalize(pattern)).replace(r"\*", r"[^.\[\]]*")
        compiled.append(re.compile(rf"{body}(?=$|[.\[])"))
    return compiled
