"""The replay settings: how every harness of `rfc sim` replays a bag, chosen once by the command."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from rfc.runtime.stall import DEFAULT_STALL_CYCLES

#: Cycles of silence after which the simulated system counts as idle.
DEFAULT_DRAIN_CYCLES = 1000


@dataclass(frozen=True)
class ReplaySettings:
    """How a harness replays a bag: the same meaning in every harness of `rfc.sim`.

    Attributes:
        drain_cycles: The cycles of silence after which the system is idle.
        stall_cycles: The cycles without a completed DMA transfer, while work is pending, after
            which the logic counts as stalled (`rfc.runtime.stall`), and the longest the
            ``busy`` bits are waited for (`rfc.sim.busy`).
        seed: Seed of the random idle of the PS→PL stream and backpressure of the PL→PS one.
        progress: Called now and then with the number of messages offered so far.
        warnings: Receives what the replay gave up waiting for (`rfc.sim.busy`).
    """

    drain_cycles: int = DEFAULT_DRAIN_CYCLES
    stall_cycles: int = DEFAULT_STALL_CYCLES
    seed: int = 1
    progress: Callable[[int], None] | None = None
    warnings: list[str] | None = None


#: The settings of a harness given none: the defaults of ``rfc sim``, nothing told or kept.
DEFAULT_SETTINGS = ReplaySettings()
