"""The processor side on a Zynq: the runtime between ROS 2 topics and the DMA devices.

`NodeCore` is everything of the generated ROS 2 node that does not need ROS: subscription
callbacks hand it serialized messages (`on_message`); a sender thread gives the PS→PL DMA the
message the software scheduler picks, one transfer at a time; a receiver thread reads PL→PS
transfers, and what they complete is published through the callback it was given. The
`Runtime` is not thread-safe, so one lock guards it; DMA calls block outside the lock.

`main` is the entry point of the generated node (`rfc.lower.ros2_node`): it reads the node's
configuration, compiles the spec, opens the devices and runs rclpy (imported only there).
"""

from __future__ import annotations

import argparse
import json
import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from rfc.runtime.account import Account
from rfc.runtime.core import Published, QueueConfig, QueuePolicy, Runtime
from rfc.runtime.dma_device import DmaChannels
from rfc.runtime.plan import RuntimePlan

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

    def _send(self) -> None:
        while True:
            with self._lock:
                while not self._stopping and not self.runtime.waiting():
                    self._work.wait()
                if self._stopping:
                    return
                chosen = self.runtime.next_transfer()
            if chosen is not None:
                self.dma.write(chosen[0].to_bytes())

    def _receive(self) -> None:
        while True:
            try:
                transfer = self.dma.read()
            except OSError:
                return
            if not transfer:
                return
            with self._lock:
                published = self.runtime.receive(transfer, self.clock(), self.clock())
                if self.runtime.waiting():
                    self._work.notify()
            for message in published:
                self.publish(message)


def load_config(path: Path) -> dict:
    """Read the node's configuration (written by ``rfc build`` beside the node)."""
    return json.loads(path.read_text())


def main(config_path: Path, argv: Sequence[str] | None = None) -> None:
    """Run the generated ROS 2 node until interrupted."""
    from rfc.driver import compile_spec
    from rfc.runtime.dma_device import FileDma, NoLogic
    from rfc.runtime.ros2 import spin

    config = load_config(config_path)
    parser = argparse.ArgumentParser(description=f"rfc ROS 2 node of {config['project']}")
    parser.add_argument("--spec", default=config["spec"], help="the system specification")
    parser.add_argument("--mm2s", default=config["devices"]["mm2s"], help="PS→PL DMA device")
    parser.add_argument("--s2mm", default=config["devices"]["s2mm"], help="PL→PS DMA device")
    parser.add_argument("--queue", default=config["queues"]["policy"], choices=list(QueuePolicy))
    parser.add_argument("--depth", type=int, default=config["queues"]["depth"])
    args, ros_arguments = parser.parse_known_args(argv)
    plan = RuntimePlan(compile_spec(args.spec))
    dma = (
        FileDma.open(config["max_transfer"], args.mm2s, args.s2mm) if plan.has_logic else NoLogic()
    )
    spin(plan, dma, QueueConfig(QueuePolicy(args.queue), args.depth), config, ros_arguments)
