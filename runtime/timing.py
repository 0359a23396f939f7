"""The PS→PL DMA in time: how long messages wait in the processor's callback queues (§4.3).

A discrete-event model around the real `Runtime`: messages arrive on their topics at given
times (periodic, possibly in bursts), wait in the callback queues, and the software scheduler
gives the PS→PL DMA one message at a time. A transfer takes ``ceil((8 + bytes) / (width / 8))``
clock cycles (one beat per cycle, the chunk header included) plus a fixed per-transfer
overhead; the logic takes every beat at once (a pass-through does), so the PS→PL DMA is the
only shared resource. What is measured per topic is the
*age* of a message when its transfer ends (from its arrival), how many were dropped, and how
many were *stale*: delivered although a newer message of the same topic had already arrived
(the paper's "no longer usable for a given subscriber").
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from rfc.runtime.core import QueueConfig, Runtime
from rfc.runtime.plan import RuntimePlan
from rfc.runtime.protocol import HEADER_SIZE


@dataclass(frozen=True)
class Traffic:
    """How one topic's messages arrive.

    Attributes:
        topic: The topic.
        data: One serialized message (its size is what matters).
        period_ns: Time between arrivals (between bursts, when `burst` > 1).
        burst: Messages arriving together each period.
        phase_ns: Time of the first arrival.
    """

    topic: str
    data: bytes
    period_ns: int
    burst: int = 1
    phase_ns: int = 0


@dataclass
class TopicFigures:
    """What happened to one topic's messages."""

    arrived: int = 0
    delivered: int = 0
    dropped: int = 0
    stale: int = 0
    ages_ns: list[int] = field(default_factory=list)

    def age_ms(self, statistic: str) -> float:
        """Mean, p95 or max age at delivery in milliseconds (0 when nothing was delivered)."""
        if not self.ages_ns:
            return 0.0
        ages = np.asarray(self.ages_ns, dtype=np.float64) / 1e6
        if statistic == "mean":
            return float(ages.mean())
        if statistic == "p95":
            return float(np.percentile(ages, 95))
        return float(ages.max())


def transfer_ns(size: int, bus_width: int, clock_mhz: float, overhead_cycles: int = 0) -> int:
    """Nanoseconds the PS→PL DMA needs for one message of `size` payload bytes."""
    beats = math.ceil((HEADER_SIZE + size) / (bus_width // 8))
    return math.ceil((beats + overhead_cycles) * 1000 / clock_mhz)


def measure(
    plan: RuntimePlan,
    traffic: Sequence[Traffic],
    queues: QueueConfig,
    duration_ns: int,
    *,
    bus_width: int,
    clock_mhz: float,
    overhead_cycles: int = 0,
) -> Mapping[str, TopicFigures]:
    """Run the traffic through the runtime and the modelled DMA for `duration_ns`.

    Args:
        plan: A system whose logic is made of pass-through chains.
        traffic: The arrivals of each subscribed topic.
        queues: The callback queues under test.
        duration_ns: Arrivals up to this time; the queues are then drained.
        bus_width: Bits of the DMA's bus (the project's).
        clock_mhz: The logic's clock (the project's).
        overhead_cycles: Fixed cycles added to every transfer (DMA set-up).

    Returns:
        Figures per topic.
    """
    runtime = Runtime(plan, queues)
    topic_of = {i.block: i.topic for i in plan.inputs}
    subscriber_topic = {c.id: topic_of[c.block] for c in plan.logic_inputs}
    figures = {t.topic: TopicFigures() for t in traffic}
    arrivals: list[tuple[int, int, int]] = []  # (time, order, traffic index)
    for index, flow in enumerate(traffic):
        for start in range(flow.phase_ns, duration_ns, flow.period_ns):
            arrivals.extend((start, index, index) for _ in range(flow.burst))
    heapq.heapify(arrivals)
    latest: dict[str, int] = {}  # topic → arrival number of its newest message
    dma_free_at = 0
    # (topic, arrival time, arrival number) of the message on the DMA; the number is its stamp
    in_transfer: tuple[str, int, int] | None = None
    count = 0
    while arrivals or in_transfer or runtime.waiting():
        next_arrival = arrivals[0][0] if arrivals else None
        if in_transfer is not None and (next_arrival is None or dma_free_at <= next_arrival):
            topic, arrived, number = in_transfer
            record = figures[topic]
            record.delivered += 1
            record.ages_ns.append(dma_free_at - arrived)
            record.stale += latest[topic] > number
            in_transfer = None
            now = dma_free_at
        elif next_arrival is not None:
            now, _, index = heapq.heappop(arrivals)
            flow = traffic[index]
            figures[flow.topic].arrived += 1
            count += 1
            latest[flow.topic] = count
            runtime.offer(flow.topic, flow.data, count, now)
        else:
            now = dma_free_at
        if in_transfer is None and (sent := runtime.next_transfer()) is not None:
            chunk, queued = sent
            start = max(now, dma_free_at)
            dma_free_at = start + transfer_ns(
                len(chunk.payload), bus_width, clock_mhz, overhead_cycles
            )
            in_transfer = (subscriber_topic[chunk.id], queued.queued_at, queued.stamp)
    for ident, counters in runtime.scheduler.counters().items():
        if subscriber_topic[ident] in figures:
            figures[subscriber_topic[ident]].dropped = counters.dropped
    return figures
