"""Callback queues and software schedulers (paper §4.3, Fig. 4)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rfc.runtime.queues import CallbackQueue, Overflow
from rfc.runtime.scheduling import PerSubscriberLRU, SharedFifo


def test_queue_keeps_the_newest_by_default():
    queue = CallbackQueue[int](2)
    assert queue.push(1) is None
    assert queue.push(2) is None
    assert queue.push(3) == 1
    assert [queue.pop(), queue.pop()] == [2, 3]
    assert (queue.counters.offered, queue.counters.delivered, queue.counters.dropped) == (3, 2, 1)


def test_queue_can_refuse_the_newest():
    queue = CallbackQueue[int](1, Overflow.DROP_NEWEST)
    queue.push(1)
    assert queue.push(2) == 2
    assert queue.pop() == 1


def test_depth_must_be_positive():
    with pytest.raises(ValueError, match="at least 1"):
        CallbackQueue[int](0)


@given(st.lists(st.tuples(st.sampled_from([0, 1, 2]), st.booleans()), max_size=300))
def test_lru_serves_every_waiting_subscriber_within_n_minus_1_others(events):
    scheduler = PerSubscriberLRU[int]({0: 4, 1: 4, 2: 4})
    waiting = {0: 0, 1: 0, 2: 0}  # per subscriber: messages waiting (mirror of the queues)
    overtaken = {0: 0, 1: 0, 2: 0}  # pops that served somebody else while it waited
    for sequence, (subscriber, pop) in enumerate(events):
        scheduler.push(subscriber, sequence)
        waiting[subscriber] = min(waiting[subscriber] + 1, 4)
        if pop:
            served, _ = scheduler.pop()
            waiting[served] -= 1
            overtaken[served] = 0
            for other in waiting:
                if other != served and waiting[other]:
                    overtaken[other] += 1
                    assert overtaken[other] <= 2, f"subscriber {other} overtaken 3 times"
    assert len(scheduler) == sum(waiting.values())
    assert sum(c.offered for c in scheduler.counters().values()) == len(events)


def test_lru_order_after_service():
    scheduler = PerSubscriberLRU[str]({0: 2, 1: 2})
    for item in ("a0", "a1"):
        scheduler.push(0, item)
    scheduler.push(1, "b0")
    assert [scheduler.pop(), scheduler.pop(), scheduler.pop(), scheduler.pop()] == [
        (0, "a0"),
        (1, "b0"),
        (0, "a1"),
        None,
    ]


def test_shared_fifo_lets_one_topic_push_out_another():
    fifo = SharedFifo[str]([0, 1], depth=3)
    fifo.push(1, "fast-0")
    for index in range(3):
        fifo.push(0, f"burst-{index}")
    assert fifo.pop() == (0, "burst-0")
    counters = fifo.counters()
    assert counters[1].dropped == 1
    assert counters[0].delivered == 1
    per_subscriber = PerSubscriberLRU[str]({0: 3, 1: 3})
    per_subscriber.push(1, "fast-0")
    for index in range(3):
        per_subscriber.push(0, f"burst-{index}")
    assert per_subscriber.pop() == (0, "burst-0")
    assert per_subscriber.pop() == (1, "fast-0")
