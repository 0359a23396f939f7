"""Software schedulers: which subscriber's message goes to the logic on the PS→PL DMA next.

Two policies, both holding messages keyed by subscriber id:

- `PerSubscriberLRU` (rfc's default, paper Fig. 4b): one bounded queue per subscriber; among the
  queues that hold messages, the one served least recently goes next — no topic starves, and a
  burst on one topic only ever displaces that topic's own old messages.
- `SharedFifo` (ROS's default, Fig. 4a): one bounded queue for everybody, served in arrival
  order; kept to reproduce the paper's comparison.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Generic, Protocol, TypeVar

from rfc.runtime.queues import CallbackQueue, Overflow, QueueCounters

T = TypeVar("T")


@dataclass(frozen=True)
class Dropped(Generic[T]):
    """A message a queue gave up, with the subscriber it was for."""

    subscriber: int
    item: T


class SoftwareScheduler(Protocol[T]):
    """What the runtime needs of a software scheduler."""

    def push(self, subscriber: int, item: T) -> Dropped[T] | None:
        """Queue a message for a subscriber; return what overflow dropped, if anything."""
        ...

    def pop(self) -> tuple[int, T] | None:
        """The next (subscriber, message) to send, or None when nothing waits."""
        ...

    def counters(self) -> Mapping[int, QueueCounters]:
        """Per-subscriber counts of offered, delivered and dropped messages."""
        ...

    def __len__(self) -> int: ...


class PerSubscriberLRU(Generic[T]):
    """One bounded queue per subscriber, served least-recently-used first.

    Args:
        depths: Queue depth per subscriber id.
        overflow: Policy of every queue when full.
    """

    def __init__(self, depths: Mapping[int, int], overflow: Overflow = Overflow.DROP_OLDEST):
        self._queues = {ident: CallbackQueue[T](depth, overflow) for ident, depth in depths.items()}
        # Least recently served first; a served subscriber moves to the end.
        self._order: list[int] = sorted(self._queues)

    def push(self, subscriber: int, item: T) -> Dropped[T] | None:
        """Queue a message on its subscriber's own queue; a full queue drops its oldest."""
        dropped = self._queue(subscriber).push(item)
        return None if dropped is None else Dropped(subscriber, dropped)

    def pop(self) -> tuple[int, T] | None:
        """Serve the least recently served subscriber that has a message waiting."""
        for position, ident in enumerate(self._order):
            queue = self._queues[ident]
            if len(queue):
                self._order.append(self._order.pop(position))
                return ident, queue.pop()
        return None

    def counters(self) -> Mapping[int, QueueCounters]:
        """Each subscriber queue's counters."""
        return {ident: queue.counters for ident, queue in self._queues.items()}

    def __len__(self) -> int:
        return sum(len(queue) for queue in self._queues.values())

    def _queue(self, subscriber: int) -> CallbackQueue[T]:
        try:
            return self._queues[subscriber]
        except KeyError:
            raise KeyError(f"no queue for subscriber {subscriber}") from None


class SharedFifo(Generic[T]):
    """ROS's single callback queue: every subscriber's messages in one bounded FIFO.

    Args:
        subscribers: The subscriber ids it serves (for the counters).
        depth: Size of the shared queue.
        overflow: Policy when full.
    """

    def __init__(
        self, subscribers: Iterable[int], depth: int, overflow: Overflow = Overflow.DROP_OLDEST
    ) -> None:
        self._queue = CallbackQueue[tuple[int, T]](depth, overflow)
        self._counters = {ident: QueueCounters() for ident in subscribers}

    def push(self, subscriber: int, item: T) -> Dropped[T] | None:
        """Queue a message behind everybody's; a full queue drops the oldest of anybody's."""
        self._counters[subscriber].offered += 1
        dropped = self._queue.push((subscriber, item))
        if dropped is None:
            return None
        self._counters[dropped[0]].dropped += 1
        return Dropped(*dropped)

    def pop(self) -> tuple[int, T] | None:
        """Serve the oldest message, whoever it is for."""
        if not len(self._queue):
            return None
        subscriber, item = self._queue.pop()
        self._counters[subscriber].delivered += 1
        return subscriber, item

    def counters(self) -> Mapping[int, QueueCounters]:
        """Counters per subscriber, as if each had its own queue."""
        return self._counters

    def __len__(self) -> int:
        return len(self._queue)
