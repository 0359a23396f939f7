"""When recorded messages arrive in a simulation: bag time on the simulated clock, idle skipped.

A replay offers each message at its recorded time, counted in clock cycles from the first
message. Simulating the long idle stretches between messages of a real bag (milliseconds:
millions of cycles) would cost far more than the messages themselves, so when the system falls
idle before the next arrival the replay offers it at once, and every later arrival moves
earlier by the cycles skipped. Messages closer together than the system needs to process them
keep their spacing, so contention in the queues is simulated as recorded.
"""

from __future__ import annotations

#: Fraction of cycles the simulated DMA idles on PS→PL and holds back PL→PS (backpressure).
IDLE_FRACTION = 0.2


class ArrivalClock:
    """Due cycles of recorded messages, shifted by the idle time skipped so far.

    Args:
        clock_mhz: The clock of the logic.
    """

    def __init__(self, clock_mhz: float) -> None:
        self.clock_mhz = clock_mhz
        self._first: int | None = None
        self._shift = 0

    def due(self, stamp_ns: int) -> int:
        """The cycle a message recorded at `stamp_ns` arrives at."""
        if self._first is None:
            self._first = stamp_ns
        return self._shift + int((stamp_ns - self._first) * self.clock_mhz // 1000)

    def offered(self, cycle: int, due: int) -> None:
        """A message due at `due` was offered at `cycle` (earlier when idle was skipped)."""
        if cycle < due:
            self._shift += cycle - due
