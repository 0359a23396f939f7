"""Callback queues on the processor side (paper §4.3, Fig. 4).

ROS keeps one callback queue shared by every subscriber (Fig. 4a): a burst on one topic delays
every other topic behind it. rfc keeps one bounded queue per subscriber (Fig. 4b) and lets a
software scheduler (`rfc.runtime.scheduling`) pick which queue feeds the PS→PL DMA next.

Overflow policy: like ROS's KEEP_LAST history, a full queue drops its *oldest* message to admit
the newest — a robot wants the freshest sample, not the first one that arrived. Every drop is
counted; nothing is lost silently.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from enum import StrEnum
from typing import Generic, TypeVar

T = TypeVar("T")


class Overflow(StrEnum):
    """What a full queue does with a new message."""

    DROP_OLDEST = "drop-oldest"
    """Admit the new message, drop the oldest waiting one (ROS KEEP_LAST; the default)."""
    DROP_NEWEST = "drop-newest"
    """Refuse the new message (keeps the order of what already waits)."""


@dataclass
class QueueCounters:
    """What happened to the messages offered to one queue."""

    offered: int = 0
    delivered: int = 0
    dropped: int = 0


class CallbackQueue(Generic[T]):
    """A bounded FIFO with an overflow policy and counters.

    Args:
        depth: How many messages may wait (≥ 1), like a ROS subscription's queue size.
        overflow: What to do when a message arrives at a full queue.
    """

    def __init__(self, depth: int, overflow: Overflow = Overflow.DROP_OLDEST) -> None:
        if depth < 1:
            raise ValueError(f"queue depth must be at least 1, not {depth}")
        self.depth = depth
        self.overflow = overflow
        self.counters = QueueCounters()
        self._items: deque[T] = deque()

    def push(self, item: T) -> T | None:
        """Offer a message; return the message dropped to make room (or refused), if any."""
        self.counters.offered += 1
        dropped = None
        if len(self._items) >= self.depth:
            self.counters.dropped += 1
            if self.overflow is Overflow.DROP_NEWEST:
                return item
            dropped = self._items.popleft()
        self._items.append(item)
        return dropped

    def pop(self) -> T:
        """Take the oldest waiting message (the queue must not be empty)."""
        self.counters.delivered += 1
        return self._items.popleft()

    def peek(self) -> T:
        """The oldest waiting message, left in place."""
        return self._items[0]

    def __len__(self) -> int:
        return len(self._items)
