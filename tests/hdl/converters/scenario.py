"""Scenarios for the cocotb pair bench: frames and messages with what must come out.

The expectations come from the oracles: the reference codec (held to rosbags by the message
layer's tests) for frames and values, `transactions` for how values appear on the ports.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rfc.lib.converters.ports import PortRole, Side, ports_of
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.transactions import Transactions, transactions
from rfc.messages.codec import encode
from tests.lib.converters.myhdl_bench import visible

_DATA = (PortRole.FIELD, PortRole.LENGTH, PortRole.COUNT)


def _hex(message: Transactions) -> dict[str, Any]:
    return {
        "record": message.record,
        "streams": {
            name: [item.hex() for item in items] for name, items in message.streams.items()
        },
        "elements": message.elements,
    }


def scenario(
    plan: Plan,
    values: Sequence[Mapping[str, Any]],
    *,
    label: str,
    seed: int,
    frames: Sequence[bytes] | None = None,
    published: Sequence[bytes] | None = None,
) -> dict[str, Any]:
    """A scenario: each message as a frame for the subscriber and as inputs for the publisher.

    Args:
        plan: The converters' plan.
        values: Flat values of each message.
        label: Names the configuration in failure messages.
        seed: Seeds the bench's idle and backpressure.
        frames: The subscriber's frames when not the codec's encoding of `values` (recorded
            frames may carry padding garbage and trailing pad bytes).
        published: What the publisher must send when not the codec's encoding of `values`.
    """
    frames = list(frames) if frames is not None else [encode(plan.layout, v) for v in values]
    if published is None:
        published = [encode(plan.layout, v) for v in values]
    messages = [transactions(plan, v) for v in values]
    pub_ports = ports_of(plan, Side.PUBLISHER)
    size = sum(map(len, frames)) + sum(map(len, published))
    return {
        "seed": seed,
        "timeout_us": 1000 + size * 5 // plan.width,
        "subscriber": _subscriber(plan, list(zip(frames, values, strict=True)), label),
        "publisher": {
            "label": label,
            "messages": [_hex(m) for m in messages],
            "frames": [f.hex() for f in published],
            "streams": sorted({p.group for p in pub_ports if p.role is PortRole.TDATA}),
        },
    }


def subscriber_scenario(
    plan: Plan, items: Sequence[tuple[bytes, Mapping[str, Any] | None]], *, label: str, seed: int
) -> dict[str, Any]:
    """A scenario for the subscriber alone: frames with their values, None when malformed."""
    size = sum(len(frame) for frame, _ in items)
    return {
        "seed": seed,
        "timeout_us": 1000 + size * 5 // plan.width + 2 * len(items),
        "subscriber": _subscriber(plan, items, label),
        "publisher": {"label": label, "messages": [], "frames": [], "streams": []},
    }


def _subscriber(
    plan: Plan, items: Sequence[tuple[bytes, Mapping[str, Any] | None]], label: str
) -> dict[str, Any]:
    ports = ports_of(plan, Side.SUBSCRIBER)
    channels = sorted({p.group for p in ports if p.role is PortRole.VALID} - {"msg"})
    expected = [
        {"error": True}
        if values is None
        else {"error": False, **_hex(visible(transactions(plan, values)))}
        for _, values in items
    ]
    return {
        "label": label,
        "frames": [frame.hex() for frame, _ in items],
        "expected": expected,
        "record": [p.name for p in ports if p.group == "msg" and p.role in _DATA],
        "streams": sorted({p.group for p in ports if p.role is PortRole.TDATA}),
        "channels": {
            name: [p.name for p in ports if p.group == name and p.role in _DATA]
            for name in channels
        },
    }


def write_scenario(path: Path, content: dict[str, Any]) -> Path:
    """Write a scenario as JSON and return its path."""
    path.write_text(json.dumps(content))
    return path
