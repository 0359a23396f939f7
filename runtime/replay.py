"""Replaying recorded messages through a system whose logic is a Python model, or absent.

The cocotb driver (`rfc.sim.cosim`) replays against simulated hardware; this module
replays when every accelerator runs in software, and against a `LogicModel` (a Python stand-in
for the programmable logic, such as `rfc.runtime.loopback.PassThroughLogic`) in tests and
measurements. Messages are offered in bag order; after each, the queues are drained through
the model, which answers every PS→PL transfer with its PL→PS transfers at once.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Protocol

from rfc.messages.rosbags_adapter import BagMessage
from rfc.runtime.core import Published, Runtime


class LogicModel(Protocol):
    """The programmable logic as a Python function of DMA transfers."""

    def transfer(self, transfer: bytes) -> list[bytes]:
        """Take one PS→PL transfer; return the PL→PS transfers it causes."""
        ...


def replay(
    runtime: Runtime,
    messages: Iterable[BagMessage],
    logic: LogicModel | None = None,
    progress: Callable[[int], None] | None = None,
) -> list[Published]:
    """Offer every message, drain the queues through the logic, and finish the account.

    Args:
        runtime: The processor side.
        messages: Input messages in time order (only subscribed topics).
        logic: The logic model; required when the system has converters in the logic.
        progress: Called with the number of messages offered so far.

    Returns:
        Everything published, in order.
    """
    if logic is None and runtime.plan.has_logic:
        raise ValueError("this system has parts in the logic; replay needs a logic model")
    published: list[Published] = []
    for count, message in enumerate(messages, 1):
        published += runtime.offer(message.topic, message.data, message.timestamp_ns)
        while (sent := runtime.next_transfer()) is not None:
            chunk, _ = sent
            assert logic is not None
            for answer in logic.transfer(chunk.to_bytes()):
                published += runtime.receive(answer, message.timestamp_ns)
        if progress is not None:
            progress(count)
    runtime.finish()
    return published
