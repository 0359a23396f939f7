"""The logic's status registers as the processor reads them: frames each subscriber dropped.

The system's top level has one 32-bit counter per subscriber and reason
(`rfc.lib.converters.malformed.status_port`, docs/protocol.md). In simulation the registers
are the top level's ports; a logic without them (a hand-written test top) reports nothing.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from rfc.lib.converters.malformed import DROP_REASONS, status_port


def read_status(dut: Any, subscribers: Mapping[int, str]) -> dict[tuple[int, str], int]:
    """The drop counters of every subscriber, by (subscriber id, reason label)."""
    counts: dict[tuple[int, str], int] = {}
    for subscriber in subscribers:
        for reason in DROP_REASONS:
            name = status_port(subscriber, reason)
            if hasattr(dut, name):
                counts[(subscriber, reason.label)] = int(getattr(dut, name).value)
    return counts
