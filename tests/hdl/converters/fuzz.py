"""Malformed frames for the subscriber, and the oracle that says which frames are malformed.

A frame is malformed when the reference codec refuses it (truncated, trailing bytes beyond
ROS 2's padding to 4, a wrong CDR encapsulation, a CDR string without its NUL, a bounded field
beyond its bound) or when a string or sequence is longer than the converter's configured
maximum. The codec also refuses strings that are not UTF-8, which the hardware does not look
at: frames whose verdict hinges on that are not used.
"""

from __future__ import annotations

import random
import struct
from collections.abc import Callable, Iterator, Mapping
from functools import partial
from typing import Any

import numpy as np

from rfc.lib.converters.steps import Loop, Payload, Plan
from rfc.messages.codec import FrameError, decode, default_values, encode
from rfc.messages.layout import FieldKind, Layout, LayoutField
from rfc.messages.rosbags_adapter import PRIMITIVE_DTYPES


def verdict(plan: Plan, frame: bytes) -> tuple[bool | None, dict[str, Any] | None]:
    """Whether the converter must reject `frame` (None: undecidable) and its values if not."""
    try:
        values = decode(plan.layout, frame)
    except FrameError as error:
        return (None, None) if "UTF-8" in str(error) else (True, None)
    payloads = {s.path: s.maximum for s in plan.steps if isinstance(s, Payload)}
    loops = {s.path: s.maximum for s in plan.steps if isinstance(s, Loop)}
    lengths = _lengths(plan.layout, values, "", payloads, loops)
    if any(length > maximum for length, maximum in lengths):
        return True, None
    return False, values


def _lengths(
    layout: Layout,
    values: Mapping[str, Any],
    prefix: str,
    payloads: dict[str, int],
    loops: dict[str, int],
) -> Iterator[tuple[int, int]]:
    """Every string's and sequence's length with its maximum."""
    for leaf in layout.fields:
        path = prefix + leaf.path
        value = values[leaf.path]
        if leaf.kind is FieldKind.STRING:
            yield len(value.encode()), payloads[path]
        elif leaf.element is not None:
            yield len(value), loops[path]
            for item in value:
                yield from _lengths(leaf.element, item, path + ".", payloads, loops)
        elif leaf.element_type == "string":
            yield len(value), loops[path]
            yield from ((len(text.encode()), payloads[path]) for text in value)
        elif leaf.kind is FieldKind.SEQUENCE:
            yield len(value), payloads[path]


KINDS = ("truncated", "trailing", "flipped", "garbage", "too long", "header")


def candidates(
    plan: Plan, valid: list[dict[str, Any]], rng: random.Random
) -> Iterator[tuple[str, bytes]]:
    """Endless frames made from valid messages, each with how it was made (one of `KINDS`)."""
    layout = plan.layout
    lengthen = _lengthener(plan)
    while True:
        values = rng.choice(valid)
        frame = encode(layout, values)
        kind = rng.choice(KINDS)
        if kind == "truncated":
            yield kind, frame[: rng.randrange(1, len(frame))]
        elif kind == "trailing":
            yield kind, frame + bytes(rng.randrange(256) for _ in range(rng.randrange(1, 10)))
        elif kind == "flipped":
            data = bytearray(frame)
            for _ in range(rng.randrange(1, 4)):
                data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
            yield kind, bytes(data)
        elif kind == "garbage":
            yield kind, bytes(rng.randrange(256) for _ in range(rng.randrange(1, 64)))
        elif kind == "too long" and lengthen is not None:
            yield kind, encode(layout, lengthen(values, rng.randrange(1, 4)))
        elif kind == "header" and layout.is_cdr:
            yield kind, struct.pack("<H", rng.randrange(0x10000)) + frame[2:]


def _lengthener(plan: Plan) -> Callable[[dict[str, Any], int], dict[str, Any]] | None:
    """Make a message's first top-level string or sequence `extra` items over its maximum."""
    for step in plan.steps:
        if isinstance(step, Payload | Loop) and step.channel == 0:
            return partial(_lengthened, step.field, step.maximum)
    return None


def _lengthened(
    leaf: LayoutField, maximum: int, values: dict[str, Any], extra: int
) -> dict[str, Any]:
    count = maximum + extra
    if leaf.kind is FieldKind.STRING:
        longer: Any = "x" * count
    elif leaf.element is not None:
        longer = [default_values(leaf.element)] * count
    elif leaf.element_type == "string":
        longer = [""] * count
    else:
        longer = np.zeros(count, dtype=PRIMITIVE_DTYPES[leaf.element_type])
    return {**values, leaf.path: longer}
