"""The processor side on a Zynq: the runtime between ROS 2 topics and the DMA devices.

`NodeCore` is everything of the generated ROS 2 node that does not need ROS: subscription
callbacks hand it serialized messages (`on_message`); a sender thread gives the PS→PL DMA the
message the software scheduler picks, one transfer at a time; a receiver thread reads PL→PS
transfers, and what they complete is published through the callback it was given. The
`Runtime` is not thread-safe, so one lock guards it; DMA calls block outside the lock. Every
`status_period` seconds, and once more when it stops, the sender asks the logic for its drop
counters (`rfc.runtime.status`): they enter the account as ``logic:<reason>``, and a change is
logged in one line.

`main` is the entry point of the generated node (`rfc.lower.node`): it reads the runtime
plan beside the node, opens the transport (`rfc.runtime.transports`) and runs rclpy or rospy
(imported only there), as the plan's middleware says. It needs no part of the compiler. A
transfer the logic does not take within the answer timeout ends the node with an error (a
bitstream that does not answer), as does any `RfcError`: one message, exit status 1.
"""

from __future__ import annotations

import argparse
import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from rfc.errors import RfcError
from rfc.messages.layout_model import Middleware
from rfc.runtime.account import Account
from rfc.runtime.core import Published, QueueConfig, QueuePolicy, Runtime
from rfc.runtime.dma_device import DmaChannels
from rfc.runtime.plan import RuntimePlan, load_plan
from rfc.runtime.protocol import ProtocolError
from rfc.runtime.status import decode_status, is_status, status_request
from rfc.runtime.transports import Device, DeviceOptions, open_transport

#: Seconds the logic may take to accept one PS→PL transfer before the node gives up.
ANSWER_TIMEOUT = 5.0
#: Seconds between two readings of the logic's drop counters.
STATUS_PERIOD = 2.0

Publish = Callable[[Published], None]


def _log(line: str) -> None:
    print(f"rfc node: {line}", file=sys.stderr, flush=True)


class NodeCore:
    """The runtime driven by ROS callbacks and two DMA threads.

    Args:
        plan: The system's routes.
        dma: The DMA channels.
        publish: Called (from any thread) with every message to publish.
        queues: The callback queues.
        clock: Time stamps in nanoseconds (ROS time in the node).
        screen: Refuse malformed messages on the processor (else the logic drops them).
        status_period: Seconds between two readings of the logic's drop counters (None: only
            when asked, `read_status`).
        log: Where a change of the logic's drop counts is reported.
    """

    def __init__(
        self,
        plan: RuntimePlan,
        dma: DmaChannels,
        publish: Publish,
        queues: QueueConfig | None = None,
        clock: Callable[[], int] = time.time_ns,
        *,
        screen: bool = True,
        status_period: float | None = None,
        log: Callable[[str], None] = _log,
    ) -> None:
        self.runtime = Runtime(plan, queues, screen=screen)
        self.dma = dma
        self.publish = publish
        self.clock = clock
        self.log = log
        self._lock = threading.Lock()
        self._work = threading.Condition(self._lock)
        self._stopping = False
        self._writing_since: float | None = None
        self._failure: RfcError | None = None
        self._status_period = status_period if plan.subscriber_names else None
        self._status_wanted = False
        self._status_due = time.monotonic() + (status_period or 0.0)
        self._status_answers = 0
        self._answered = threading.Condition(self._lock)
        self._logic_drops: dict[tuple[str, str], int] = {}
        self._threads = [
            threading.Thread(target=self._send, name="rfc-mm2s", daemon=True),
            threading.Thread(target=self._receive, name="rfc-s2mm", daemon=True),
        ]

    @property
    def topics(self) -> tuple[str, ...]:
        """The topics to subscribe to."""
        return self.runtime.topics

    def start(self) -> None:
        """Start the DMA threads."""
        for thread in self._threads:
            thread.start()

    def on_message(self, topic: str, data: bytes) -> None:
        """A subscription received a serialized message."""
        with self._lock:
            published = self.runtime.offer(topic, data, self.clock(), self.clock())
            self._work.notify()
        for message in published:
            self.publish(message)

    def read_status(self, timeout: float) -> bool:
        """Ask the logic for its drop counters and wait up to `timeout` s for the answer.

        Returns:
            Whether the answer came (the counts are then in the account).
        """
        with self._lock:
            answers = self._status_answers
            self._status_wanted = True
            self._work.notify()
            return self._answered.wait_for(lambda: self._status_answers > answers, timeout)

    def stop(self, timeout: float = 1.0) -> Account:
        """Read the logic's counters once more, stop sending, close the DMA; the account."""
        if self._status_period is not None and self._threads[0].is_alive():
            self.read_status(timeout)
        with self._lock:
            self._stopping = True
            self._work.notify_all()
        sender, receiver = self._threads
        if sender.ident is not None:
            sender.join(timeout)
        self.dma.close()
        if receiver.ident is not None:
            receiver.join(timeout)
        with self._lock:
            self.runtime.finish()
            return self.runtime.account

    def check(self, timeout: float = ANSWER_TIMEOUT) -> None:
        """Raise when the logic has not taken a transfer for `timeout` seconds, or failed.

        Raises:
            RfcError: The logic does not answer, or a ROS-SW accelerator fed by it failed.
        """
        if self._failure is not None:
            raise self._failure
        since = self._writing_since
        if since is not None and time.monotonic() - since > timeout:
            raise RfcError(
                f"the logic has not taken a PS→PL transfer in {timeout:g} s",
                hint="check that the bitstream of this build is loaded and its DMA runs",
            )

    def _send(self) -> None:
        while True:
            with self._lock:
                while not (self._stopping or self.runtime.waiting() or self._status_time()):
                    self._work.wait(self._status_wait())
                if self._stopping:
                    return
                if self._status_time():
                    self._status_wanted = False
                    if self._status_period is not None:
                        self._status_due = time.monotonic() + self._status_period
                    transfer = status_request().to_bytes()
                else:
                    chosen = self.runtime.next_transfer()
                    transfer = chosen[0].to_bytes() if chosen is not None else b""
            if transfer:
                self._writing_since = time.monotonic()
                try:
                    self.dma.write(transfer)
                except OSError:  # the DMA closed under a write: the node is stopping
                    return
                self._writing_since = None

    def _status_time(self) -> bool:
        """Whether the logic's counters are to be read now (the lock held)."""
        due = self._status_period is not None and time.monotonic() >= self._status_due
        return self._status_wanted or due

    def _status_wait(self) -> float | None:
        """Seconds until the next periodic reading, if any (the lock held)."""
        if self._status_period is None:
            return None
        return max(0.0, self._status_due - time.monotonic())

    def _take_status(self, transfer: bytes) -> None:
        """Put the logic's answer into the account; log what changed (the lock held)."""
        names = self.runtime.plan.subscriber_names
        try:
            counts = decode_status(transfer, names)
        except ProtocolError as error:
            self.runtime.account.drop("logic", f"protocol:{error.reason}")
            return
        self.runtime.logic_drops(counts)
        drops = {(names[s], f"logic:{r}"): n for (s, r), n in counts.items() if n}
        if drops != self._logic_drops:
            self._logic_drops = drops
            listed = ", ".join(f"{where} {reason} {n}" for (where, reason), n in drops.items())
            self.log(f"frames the logic dropped: {listed or 'none'}")
        self._status_answers += 1
        self._answered.notify_all()

    def _receive(self) -> None:
        while True:
            try:
                transfer = self.dma.read()
            except OSError:
                return
            if not transfer:
                return
            if is_status(transfer):
                with self._lock:
                    self._take_status(transfer)
                continue
            with self._lock:
                try:
                    published = self.runtime.receive(transfer, self.clock(), self.clock())
                except RfcError as error:  # a ROS-SW function failed: `check` reports it
                    self._failure = error
                    return
                if self.runtime.waiting():
                    self._work.notify()
            for message in published:
                self.publish(message)


@dataclass(frozen=True)
class NodeSetup:
    """What `main` hands the middleware's ``spin`` (`rfc.runtime.ros1`, `rfc.runtime.ros2`).

    Attributes:
        plan: The system's routes.
        open_dma: Opens the DMA channels (the node does so before it joins the ROS graph).
        queues: The callback queues.
        screen: Refuse malformed messages on the processor (else the logic drops them).
        status_period: Seconds between two readings of the logic's drop counters.
        answer_timeout: Seconds the logic may take to accept a transfer.
        ros_arguments: The command line's arguments for the ROS client library.
    """

    plan: RuntimePlan
    open_dma: Callable[[], DmaChannels]
    queues: QueueConfig
    screen: bool
    status_period: float
    answer_timeout: float
    ros_arguments: tuple[str, ...]

    def core(self, dma: DmaChannels, publish: Publish, clock: Callable[[], int]) -> NodeCore:
        """The node's core on `dma`, publishing with the middleware's `publish` and clock."""
        return NodeCore(
            self.plan,
            dma,
            publish,
            self.queues,
            clock,
            screen=self.screen,
            status_period=self.status_period,
        )


def parse_options(
    plan: RuntimePlan, argv: Sequence[str] | None
) -> tuple[argparse.Namespace, list[str]]:
    """The node's options (defaults from the plan) and the ROS arguments left over."""
    middleware = plan.middleware.label
    parser = argparse.ArgumentParser(description=f"rfc {middleware} node of {plan.project}")
    devices = plan.document.get("devices", {})
    queues = plan.document.get("queues", {})
    parser.add_argument(
        "--device",
        default=Device.DMA,
        choices=list(Device),
        type=Device,
        help="how transfers reach the logic (sim: GHDL on the build's logic)",
    )
    parser.add_argument("--mm2s", default=devices.get("mm2s", ""), help="PS→PL DMA device")
    parser.add_argument("--s2mm", default=devices.get("s2mm", ""), help="PL→PS DMA device")
    parser.add_argument("--bitstream", default="", help="the bitstream (--device pynq)")
    parser.add_argument("--dma", default="axi_dma_0", help="the AXI DMA's name (--device pynq)")
    parser.add_argument(
        "--queue",
        default=queues.get("policy", QueuePolicy.PER_SUBSCRIBER),
        choices=list(QueuePolicy),
    )
    parser.add_argument("--depth", type=int, default=queues.get("depth", 10))
    parser.add_argument(
        "--send-malformed",
        action="store_true",
        help="send malformed messages to the logic, which drops and counts them",
    )
    parser.add_argument(
        "--status-period",
        type=float,
        default=STATUS_PERIOD,
        help="seconds between two readings of the logic's drop counters",
    )
    parser.add_argument(
        "--answer-timeout",
        type=float,
        default=ANSWER_TIMEOUT,
        help="seconds the logic may take to accept a transfer",
    )
    args, ros_arguments = parser.parse_known_args(argv)
    return args, ros_arguments


def main(plan_path: Path, argv: Sequence[str] | None = None) -> None:
    """Run the generated node until interrupted; errors end it with one message, status 1."""
    try:
        plan = load_plan(plan_path)
        args, ros_arguments = parse_options(plan, argv)
        if args.depth < 1:
            raise RfcError(f"--depth must be at least 1, not {args.depth}")
        if not args.status_period > 0:
            raise RfcError(f"--status-period must be a positive number, not {args.status_period}")
        if plan.middleware is Middleware.ROS1:
            from rfc.runtime.ros1 import spin
        else:
            from rfc.runtime.ros2 import spin
        options = DeviceOptions(args.device, args.mm2s, args.s2mm, args.bitstream, args.dma)
        spin(
            NodeSetup(
                plan,
                lambda: open_transport(plan, options),
                QueueConfig(QueuePolicy(args.queue), args.depth),
                screen=not args.send_malformed,
                status_period=args.status_period,
                answer_timeout=args.answer_timeout,
                ros_arguments=tuple(ros_arguments),
            )
        )
    except RfcError as error:
        print(f"rfc node: {error}", file=sys.stderr)
        raise SystemExit(1) from None
