"""The processor side on a Zynq: the runtime between ROS 2 topics and the DMA devices.

`NodeCore` is everything of the generated ROS 2 node that does not need ROS: subscription
callbacks hand it serialized messages (`on_message`); a sender thread gives the PS→PL DMA the
message the software scheduler picks, one transfer at a time; a receiver thread reads PL→PS
transfers, and what they complete is published through the callback it was given. The
`Runtime` is not thread-safe, so one lock guards it; DMA calls block outside the lock.

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
from pathlib import Path

from rfc.runtime.account import Account
from rfc.runtime.core import Published, QueueConfig, QueuePolicy, Runtime
from rfc.runtime.dma_device import DmaChannels
from rfc.runtime.errors import RfcError
from rfc.runtime.layout import Middleware
from rfc.runtime.plan import RuntimePlan, load_plan
from rfc.runtime.transports import Device, DeviceOptions, open_transport

#: Seconds the logic may take to accept one PS→PL transfer before the node gives up.
ANSWER_TIMEOUT = 5.0

Publish = Callable[[Published], None]


class NodeCore:
    """The runtime driven by ROS callbacks and two DMA threads.

    Args:
        plan: The system's routes.
        dma: The DMA channels.
        publish: Called (from any thread) with every message to publish.
        queues: The callback queues.
        clock: Time stamps in nanoseconds (ROS time in the node).
    """

    def __init__(
        self,
        plan: RuntimePlan,
        dma: DmaChannels,
        publish: Publish,
        queues: QueueConfig | None = None,
        clock: Callable[[], int] = time.time_ns,
    ) -> None:
        self.runtime = Runtime(plan, queues)
        self.dma = dma
        self.publish = publish
        self.clock = clock
        self._lock = threading.Lock()
        self._work = threading.Condition(self._lock)
        self._stopping = False
        self._writing_since: float | None = None
        self._failure: RfcError | None = None
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

    def stop(self, timeout: float = 1.0) -> Account:
        """Stop sending, close the DMA, and return the account."""
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
                while not self._stopping and not self.runtime.waiting():
                    self._work.wait()
                if self._stopping:
                    return
                chosen = self.runtime.next_transfer()
            if chosen is not None:
                self._writing_since = time.monotonic()
                self.dma.write(chosen[0].to_bytes())
                self._writing_since = None

    def _receive(self) -> None:
        while True:
            try:
                transfer = self.dma.read()
            except OSError:
                return
            if not transfer:
                return
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
        if plan.middleware is Middleware.ROS1:
            from rfc.runtime.ros1 import spin
        else:
            from rfc.runtime.ros2 import spin
        options = DeviceOptions(args.device, args.mm2s, args.s2mm, args.bitstream, args.dma)
        queues = QueueConfig(QueuePolicy(args.queue), args.depth)
        spin(plan, lambda: open_transport(plan, options), queues, args, ros_arguments)
    except RfcError as error:
        print(f"rfc node: {error}", file=sys.stderr)
        raise SystemExit(1) from None
