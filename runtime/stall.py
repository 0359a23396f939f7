"""The stall watchdog of simulated replays: a logic that stops moving is an error, not a hang.

While work is pending — a PS→PL transfer under way, messages waiting for the logic, a PL→PS
transfer or message begun — some DMA transfer must complete now and then. When none has for
`stall_cycles` plus four times the longest transfer that may be moving (in beats: the longest
completed so far, the PS→PL transfer under way, and — while a PL→PS transfer is under way — the
largest frame a publisher can send), the replay stops with an error that says what was pending.
`AnswerWait` keeps a replay from calling a logic idle while it may still answer a large frame.
Both simulation backends use them.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from rfc.errors import RfcError
from rfc.runtime.core import Runtime
from rfc.runtime.protocol import Chunk

#: Default cycles without a completed transfer, while work is pending, that count as a stall.
DEFAULT_STALL_CYCLES = 100_000


class StallError(RfcError):
    """The simulated logic stopped completing transfers while work was pending."""


@dataclass
class StallWatch:
    """Watch one replay's DMA transfers for a stall.

    Attributes:
        stall_cycles: Cycles without a completed transfer that count as a stall (plus four
            times the longest transfer that may be moving).
        lanes: Bytes per beat of the DMA streams.
        largest_output: Bytes of the largest PL→PS transfer a publisher can send.
    """

    stall_cycles: int
    lanes: int
    largest_output: int = 0
    _last: int = field(default=0, init=False)
    _longest: int = field(default=0, init=False)

    def completed(self, cycle: int, transfer_bytes: int) -> None:
        """A transfer of `transfer_bytes` (chunk header included) completed at `cycle`."""
        self._last = cycle
        self._longest = max(self._longest, self._beats(transfer_bytes))

    def window(self, sending_bytes: int = 0, receiving: bool = False) -> int:
        """Cycles without a completed transfer that count as a stall now.

        Args:
            sending_bytes: Bytes of the PS→PL transfer under way (0: none).
            receiving: Whether a PL→PS transfer is under way.
        """
        moving = max(
            self._longest,
            self._beats(sending_bytes),
            self._beats(self.largest_output) if receiving else 0,
        )
        return self.stall_cycles + 4 * moving

    def check(
        self,
        cycle: int,
        busy: bool,
        pending: Callable[[], str],
        sending_bytes: int = 0,
        receiving: bool = False,
    ) -> None:
        """Raise `StallError` when work is pending and nothing completed for the window.

        Args:
            cycle: The current cycle.
            busy: Whether work is pending (when not, the watch rests).
            pending: Says what is pending, for the error.
            sending_bytes: Bytes of the PS→PL transfer under way (0: none).
            receiving: Whether a PL→PS transfer is under way.
        """
        if not busy:
            self._last = cycle
            return
        if cycle - self._last > self.window(sending_bytes, receiving):
            raise StallError(
                f"the logic stalled: no DMA transfer completed for {cycle - self._last:,} cycles "
                f"(cycle {cycle:,}) while {pending()}",
                hint="if the logic legitimately needs longer between transfers, raise "
                "--stall-cycles; otherwise an accelerator or converter waits for something "
                "that never comes (a handshake it does not answer)",
            )

    def _beats(self, transfer_bytes: int) -> int:
        return math.ceil(transfer_bytes / self.lanes)


@dataclass
class AnswerWait:
    """How long a replay waits for the logic's answer to a transfer before calling it idle.

    A subscriber's frame guard holds a whole frame before handing any of it on, so the answer
    to a transfer of N beats may begin N cycles and more after the transfer ends: far longer
    than the drain window when frames are large. Each completed PS→PL transfer of N beats is
    awaited for 4N cycles, or until a PL→PS transfer completes (the oldest first); a logic that
    answers nothing (it drops the message) costs those cycles and no more.

    Attributes:
        lanes: Bytes per beat of the DMA streams.
    """

    lanes: int
    _deadlines: deque[int] = field(default_factory=deque, init=False)

    def sent(self, cycle: int, transfer_bytes: int) -> None:
        """A PS→PL transfer of `transfer_bytes` completed at `cycle`."""
        self._deadlines.append(cycle + 4 * math.ceil(transfer_bytes / self.lanes))

    def answered(self) -> None:
        """A PL→PS transfer completed: the oldest transfer awaited has its answer."""
        if self._deadlines:
            self._deadlines.popleft()

    def awaiting(self, cycle: int) -> bool:
        """Whether an answer may still come at `cycle`."""
        while self._deadlines and self._deadlines[0] <= cycle:
            self._deadlines.popleft()
        return bool(self._deadlines)


def largest_output(runtime: Runtime) -> int:
    """Bytes of the largest PL→PS transfer the design's publishers can send (header included)."""
    return runtime.plan.max_transfer


def pending_work(runtime: Runtime, sending: Chunk | None, receiving: bool) -> str:
    """What a replay waits for, in words: the transfers under way and the messages waiting.

    Args:
        runtime: The processor side.
        sending: The PS→PL chunk under way, if one is.
        receiving: Whether a PL→PS transfer has begun and not ended.
    """
    parts = []
    if sending is not None:
        name = runtime.plan.subscriber_names.get(sending.id, f"id {sending.id}")
        parts.append(
            f"the logic had not taken all of a {sending.size}-byte PS→PL transfer "
            f"to subscriber '{name}'"
        )
    if receiving:
        parts.append("a PL→PS transfer had begun and not ended (no tlast)")
    if unfinished := runtime.unfinished_publishers():
        names = ", ".join(f"'{name}'" for name in unfinished)
        parts.append(f"publisher {names} had begun a message and not finished it")
    if waiting := runtime.waiting():
        parts.append(f"{waiting} message{'s' if waiting > 1 else ''} waited for the logic")
    return "; ".join(parts) or "work was pending"
