"""The processor side of a system as a state machine, free of any I/O (sans-IO).

`Runtime` takes messages from topics (`offer`), hands the PS→PL DMA its next chunk
(`next_transfer`, chosen by the software scheduler among the per-subscriber queues), and takes
PL→PS transfers back (`receive`, reassembled by publisher id). ROS-SW accelerators run inside
it. Whatever drives it — bag replay against a software model or a GHDL simulation, or the ROS 2
node on a Zynq — supplies the time stamps and moves the bytes; so every transport shares one
routing, one scheduler and one account.

Time stamps: a message keeps the stamp of the input it came from. Outputs of the logic get the
stamp the driver passes to `receive` (the replay: the stamp of the newest input taken so far).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from enum import StrEnum

from rfc.errors import RfcError
from rfc.messages.codec import FrameError, decode
from rfc.runtime.account import Account
from rfc.runtime.plan import LogicInput, Route, RuntimePlan, TopicInput, ToSoftware, ToTopic
from rfc.runtime.protocol import Chunk, ProtocolError, Reassembler, message_chunk
from rfc.runtime.queues import Overflow
from rfc.runtime.scheduling import PerSubscriberLRU, SharedFifo, SoftwareScheduler

#: Default depth of each callback queue (a ROS subscription's usual queue size).
DEFAULT_DEPTH = 10


# An enum then a record, like rfc.ir's DmaDirection in shape only: callback queues.
class QueuePolicy(StrEnum):
    """How the processor queues messages for the PS→PL DMA (paper Fig. 4)."""

    PER_SUBSCRIBER = "per-subscriber"
    """One bounded queue per subscriber, served least recently used first (rfc's default)."""
    SHARED_FIFO = "shared-fifo"
    """One bounded queue for every subscriber, served in arrival order (ROS's default)."""


@dataclass(frozen=True)
class QueueConfig:
    """The callback queues: policy, depth (per queue, or of the shared one) and overflow."""

    policy: QueuePolicy = QueuePolicy.PER_SUBSCRIBER
    depth: int = DEFAULT_DEPTH
    overflow: Overflow = Overflow.DROP_OLDEST


@dataclass(frozen=True)
class Published:
    """A message the system publishes on a ROS topic."""

    topic: str
    message: str
    stamp: int
    data: bytes


@dataclass(frozen=True)
class Queued:
    """A message waiting for the PS→PL DMA: its bytes, stamp and when it was queued."""

    data: bytes
    stamp: int
    queued_at: int


class Runtime:
    """Queues, software scheduler, reassembly, software accelerators and the account.

    Args:
        plan: The routes of the system.
        queues: The callback queue configuration.
        screen: Refuse malformed messages here (``malformed``); else send them to the logic,
            whose subscribers drop them (``logic:<reason>``, read with `logic_drops`).
    """

    def __init__(
        self, plan: RuntimePlan, queues: QueueConfig | None = None, *, screen: bool = True
    ) -> None:
        self.plan = plan
        self.queues = queues or QueueConfig()
        self.screen = screen
        ids = [c.id for c in plan.logic_inputs]
        self.scheduler: SoftwareScheduler[Queued] = (
            PerSubscriberLRU(dict.fromkeys(ids, self.queues.depth), self.queues.overflow)
            if self.queues.policy is QueuePolicy.PER_SUBSCRIBER
            else SharedFifo(ids, self.queues.depth, self.queues.overflow)
        )
        self.account = Account()
        self.software = plan.software_accelerators()
        self._reassembler = Reassembler()
        self._inputs: dict[str, list[TopicInput]] = {}
        for topic_input in plan.inputs:
            self._inputs.setdefault(topic_input.topic, []).append(topic_input)

    @property
    def topics(self) -> tuple[str, ...]:
        """The topics the system subscribes to."""
        return tuple(self._inputs)

    def offer(self, topic: str, data: bytes, stamp: int, now: int = 0) -> list[Published]:
        """A message arrived on a subscribed topic.

        Args:
            topic: Its topic (one the system subscribes to).
            data: Its serialized bytes.
            stamp: Its time stamp in nanoseconds, inherited by what it causes.
            now: The driver's clock, recorded for queue-age measurements.

        Returns:
            What software parts published in response.
        """
        self.account.received[topic] += 1
        published: list[Published] = []
        for topic_input in self._inputs[topic]:
            self._deliver(topic_input.routes, data, stamp, now, published)
        return published

    def next_transfer(self) -> tuple[Chunk, Queued] | None:
        """The chunk the software scheduler sends to the logic next, if any message waits."""
        chosen = self.scheduler.pop()
        if chosen is None:
            return None
        subscriber, queued = chosen
        self.account.to_logic[self.plan.subscriber_names[subscriber]] += 1
        return message_chunk(subscriber, queued.data), queued

    def waiting(self) -> int:
        """Messages waiting in the callback queues."""
        return len(self.scheduler)

    def receive(self, transfer: bytes, stamp: int, now: int = 0) -> list[Published]:
        """A PL→PS DMA transfer arrived; route the message it completes, if any."""
        try:
            chunk = Chunk.from_bytes(transfer)
        except ProtocolError as error:
            self.account.drop("logic", f"protocol:{error.reason}")
            return []
        routes = self.plan.logic_outputs.get(chunk.id)
        if routes is None:
            self.account.drop("logic", "protocol:id")
            return []
        where = self.plan.publisher_names[chunk.id]
        try:
            message = self._reassembler.feed(chunk)
        except ProtocolError as error:
            self.account.drop(where, f"protocol:{error.reason}")
            return []
        if message is None:
            return []
        self.account.from_logic[where] += 1
        published: list[Published] = []
        self._deliver(routes, message, stamp, now, published)
        return published

    def unfinished_publishers(self) -> list[str]:
        """The publishers whose PL→PS message has started and not finished."""
        return [self.plan.publisher_names.get(i, f"id {i}") for i in self._reassembler.pending()]

    def in_flight(self) -> bool:
        """Whether a PL→PS message has started and not finished."""
        return bool(self._reassembler.pending())

    def finish(self) -> None:
        """End the run: count what is still unfinished or waiting as dropped."""
        while (left := self.scheduler.pop()) is not None:
            self.account.drop(self.plan.subscriber_names[left[0]], "unsent")
        for ident in self._reassembler.pending():
            self.account.drop(self.plan.publisher_names[ident], "protocol:unfinished")
        for name, accelerator in self.software.items():
            if accelerator.waiting():
                self.account.drop(name, "unmatched", accelerator.waiting())

    def logic_drops(self, counts: Mapping[tuple[int, str], int]) -> None:
        """Take what the logic's subscribers dropped, by (subscriber id, reason) as it reports.

        The logic counts from its reset, so a reading replaces the previous one.
        """
        for (subscriber, reason), count in counts.items():
            key = (self.plan.subscriber_names[subscriber], f"logic:{reason}")
            if count:
                self.account.dropped[key] = count
            else:
                self.account.dropped.pop(key, None)

    def _deliver(
        self, routes: Iterable[Route], data: bytes, stamp: int, now: int, out: list[Published]
    ) -> None:
        for route in routes:
            if isinstance(route, LogicInput):
                refused = self._refused_by_logic(route, data)
                if refused is not None:
                    self.account.drop(route.block, refused)
                    continue
                dropped = self.scheduler.push(route.id, Queued(data, stamp, now))
                if dropped is not None:
                    self.account.drop(self.plan.subscriber_names[dropped.subscriber], "overflow")
            elif isinstance(route, ToTopic):
                self._publish(route, data, stamp, out)
            else:
                self._run_software(route, data, stamp, now, out)

    def _refused_by_logic(self, subscriber: LogicInput, data: bytes) -> str | None:
        """Why the subscriber converter would drop this message, if it would.

        It drops what is not a message of its type and what holds a string or sequence longer
        than the maxima it was built for; both are counted here rather than lost in the logic.
        """
        if not self.screen:
            return None
        layout = subscriber.layout
        try:
            values = decode(layout, data)
        except FrameError:
            return "malformed"
        return None if self.plan.maxima.beyond(layout, values) is None else "maximum"

    def _publish(self, route: ToTopic, data: bytes, stamp: int, out: list[Published]) -> None:
        try:
            shaped = route.shaper.shape(data)
        except FrameError:
            self.account.drop(route.block, "malformed")
            return
        self.account.published[route.topic] += 1
        out.append(Published(route.topic, route.message, stamp, shaped))

    def _run_software(
        self, route: ToSoftware, data: bytes, stamp: int, now: int, out: list[Published]
    ) -> None:
        try:
            message = self.plan.messages.deserialize(route.shaper.shape(data), route.message)
        except FrameError:
            self.account.drop(route.name, "malformed")
            return
        accelerator = self.software[route.block]
        if accelerator.take(route.port, message):
            self.account.drop(route.name, "superseded")
        if not accelerator.ready():
            return
        self.account.software_calls[route.block] += 1
        results = accelerator.fire()
        port_routes = self.plan.software_outputs[route.block]
        for routes, result, message_type in zip(
            port_routes, results, accelerator.block.output_types, strict=True
        ):
            if result is not None:
                self._deliver(
                    routes, self._serialize(route.block, result, message_type), stamp, now, out
                )

    def _serialize(self, block: str, message: object, message_type: str) -> bytes:
        try:
            return self.plan.messages.serialize(message, message_type)
        except Exception as exc:  # rosbags refused what the user's function built
            raise RfcError(
                f"ROS-SW accelerator '{block}' returned a message rosbags cannot serialize "
                f"as {message_type}: {type(exc).__name__}: {exc}"
            ) from None
