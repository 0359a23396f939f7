"""The account of a run: every message in, out, and dropped, with the reason it was dropped.

Nothing is lost silently: a message taken from a topic either reaches the logic or a software
accelerator, or is counted as dropped where it was dropped and why. Reasons:

- ``overflow``: a full callback queue gave it up (the oldest waiting, under KEEP_LAST).
- ``malformed``: bytes that are not a valid message of their type.
- ``maximum``: a string or sequence longer than the project's ``maxima``, which the logic's
  subscriber converter was built for (it would drop the message).
- ``logic:<reason>``: a frame the logic's subscriber dropped (``truncated``, ``maximum``,
  ``trailing``, ``encoding``), read from its status registers; only when the processor sends
  malformed messages instead of refusing them (``rfc sim --send-malformed``).
- ``protocol:<reason>``: PL→PS chunks breaking the wire protocol (docs/protocol.md), counted
  per message lost; ``protocol:id`` is a chunk of a publisher id the system does not have,
  ``protocol:unfinished`` a message still incomplete when the run ended.
- ``unsent``: it still waited in a callback queue when the run ended.
- ``superseded``: a newer message replaced it on an input of a multi-input ROS-SW accelerator
  before that accelerator fired; ``unmatched``: it still waited there when the run ended.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import Any


@dataclass
class Account:
    """Counters of one run.

    Attributes:
        received: Messages taken from each input topic.
        published: Messages written to each output topic.
        to_logic: PS→PL messages sent, by subscriber converter name.
        from_logic: PL→PS messages completed, by publisher converter name.
        software_calls: Calls of each ROS-SW accelerator.
        dropped: Messages dropped, by (where, reason); where is a block or ``Block.port``.
    """

    received: Counter[str] = field(default_factory=Counter)
    published: Counter[str] = field(default_factory=Counter)
    to_logic: Counter[str] = field(default_factory=Counter)
    from_logic: Counter[str] = field(default_factory=Counter)
    software_calls: Counter[str] = field(default_factory=Counter)
    dropped: Counter[tuple[str, str]] = field(default_factory=Counter)

    def drop(self, where: str, reason: str, count: int = 1) -> None:
        """Count messages dropped at `where` for `reason`."""
        self.dropped[(where, reason)] += count

    def dropped_by_reason(self) -> Counter[str]:
        """Drops summed over places."""
        totals: Counter[str] = Counter()
        for (_, reason), count in self.dropped.items():
            totals[reason] += count
        return totals

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready document of every counter."""
        return {
            "received": dict(self.received),
            "published": dict(self.published),
            "to_logic": dict(self.to_logic),
            "from_logic": dict(self.from_logic),
            "software_calls": dict(self.software_calls),
            "dropped": [
                {"where": where, "reason": reason, "count": count}
                for (where, reason), count in sorted(self.dropped.items())
            ],
        }

    @classmethod
    def from_json(cls, document: dict[str, Any]) -> Account:
        """Rebuild an account written by `to_json` (how a simulation reports back)."""
        return cls(
            received=Counter(document["received"]),
            published=Counter(document["published"]),
            to_logic=Counter(document["to_logic"]),
            from_logic=Counter(document["from_logic"]),
            software_calls=Counter(document["software_calls"]),
            dropped=Counter({(d["where"], d["reason"]): d["count"] for d in document["dropped"]}),
        )
