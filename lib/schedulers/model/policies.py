"""Compute Condition and Set Grant of the six algorithms, vectorized (one class per family).

Each class mirrors the hardware module of the same family in `rfc.lib.schedulers`: the same
registers, reset values, widths and update rules, on arrays with a batch dimension R.
Counters of the timed algorithms are biased by H = 2^(bits-1) and saturate at 0, as in hardware.
"""

from __future__ import annotations

import numpy as np

from rfc.lib.schedulers.model.selection import (
    first_candidate,
    holder_first,
    least_key,
    least_key_holder_first,
    tree_least_modular,
)
from rfc.lib.schedulers.model.statechart import BoolArray, Cycle, IntArray


def counter_type(bits: int) -> type[np.signedinteger]:
    """The narrowest NumPy integer that holds a biased counter (and the difference of two)."""
    return np.int32 if bits <= 30 else np.int64


class FixedPriority:
    """NPFP and PFP: no table; the lowest requesting index wins."""

    tracks_arrivals = False

    def __init__(self, preemptive: bool) -> None:
        self.preemptive = preemptive

    def reset(self) -> None:
        """Nothing to reset: priorities are the indices."""

    def compute(self, cycle: Cycle) -> BoolArray | None:
        """Fixed priorities need no computation."""
        return None

    def select(self, cycle: Cycle, rows: IntArray | None) -> IntArray:
        """The lowest requesting index."""
        return first_candidate(cycle.candidates if rows is None else cycle.candidates[rows])

    def commit(self, cycle: Cycle, selected: BoolArray, best: IntArray) -> None:
        """Nothing to update."""


class LeastRecentlyUsed:
    """LRU: a rank per input (0 = top); the input granted moves to the bottom (rank N-1)."""

    preemptive = False
    tracks_arrivals = False

    def __init__(self, n: int, batch: int) -> None:
        self._n, self._batch = n, batch
        self.reset()

    def reset(self) -> None:
        """Ranks start as the indices: input 0 on top."""
        self.rank = np.tile(np.arange(self._n, dtype=np.int32), (self._batch, 1))

    def compute(self, cycle: Cycle) -> BoolArray | None:
        """Ranks change only when a grant is given (see `commit`)."""
        return None

    def select(self, cycle: Cycle, rows: IntArray | None) -> IntArray:
        """The requester highest in the list."""
        if rows is None:
            return least_key(cycle.candidates, self.rank)
        return least_key(cycle.candidates[rows], self.rank[rows])

    def commit(self, cycle: Cycle, selected: BoolArray, best: IntArray) -> None:
        """The newly granted input goes to the bottom; those below it move up one place."""
        rows = np.nonzero(selected & (best >= 0))[0]
        if rows.size == 0:
            return
        chosen = self.rank[rows, best[rows]]
        self.rank[rows] -= self.rank[rows] > chosen[:, None]
        self.rank[rows, best[rows]] = self._n - 1


class Countdown:
    """Per-input counters that load on arrival and count down while pending (LOEDF, LST).

    Mirrors `rfc.lib.schedulers.countdown`: biased by H, saturating at 0; Set Grant compares the
    counters' next values, so a new message competes in the cycle it arrives; the holder wins
    ties.

    Args:
        load: int[R, N] biased value each counter takes on arrival.
        keep_while_moving: The counter of the input whose beat moves does not count (LST).
    """

    preemptive = True
    tracks_arrivals = True

    def __init__(self, load: IntArray, keep_while_moving: bool) -> None:
        self._load = load
        self._keep_while_moving = keep_while_moving
        self.reset()

    def reset(self) -> None:
        """Counters reset to 0 (the most urgent value); they load on each arrival."""
        self.counter = np.zeros_like(self._load)
        self._next = self.counter

    def compute(self, cycle: Cycle) -> BoolArray | None:
        """Load arrivals; pending messages count down (LST: unless their beat moves)."""
        assert cycle.pending is not None
        assert cycle.arrival is not None
        counting = cycle.pending & (self.counter > 0)
        if self._keep_while_moving:
            moving = np.nonzero(cycle.transfer >= 0)[0]
            counting[moving, cycle.transfer[moving]] = False
        self._next = self.counter - counting
        np.copyto(self._next, self._load, where=cycle.arrival)
        return None

    def select(self, cycle: Cycle, rows: IntArray | None) -> IntArray:
        """The smallest next value among candidates; the holder keeps the grant on a tie."""
        return least_key_holder_first(cycle.candidates, self._next, cycle.owner)

    def commit(self, cycle: Cycle, selected: BoolArray, best: IntArray) -> None:
        """Register the counters' next values."""
        self.counter = self._next


class LatencyOptimizedEdf(Countdown):
    """LOEDF: a down-counter per input holds the cycles left to its deadline.

    On arrival the counter loads D_i - 1 (the value it has one cycle later); every cycle a
    message is pending it counts down, saturating at -H.
    """

    def __init__(self, deadline: IntArray, bits: int) -> None:
        load = deadline - 1 + (1 << (bits - 1))
        super().__init__(load.astype(counter_type(bits)), keep_while_moving=False)


class LeastSlackTime(Countdown):
    """LST: a slack counter per input, s = d - t - c (deadline, now, beats still to send).

    On arrival it loads D_i - T_i - 1; each cycle a pending message does not move a beat its
    slack drops by one (saturating at -H), while the input moving a beat keeps its slack.
    """

    def __init__(self, transfer: IntArray, deadline: IntArray, bits: int) -> None:
        load = deadline - transfer - 1 + (1 << (bits - 1))
        super().__init__(load.astype(counter_type(bits)), keep_while_moving=True)


class ResourceOptimizedEdf:
    """ROEDF: absolute deadlines on a wrapping timer, registered one arrival per cycle.

    A free-running timer counts cycles. While requests wait to be registered (lowest index
    first, one per cycle, through one shared adder: deadline = timer + D_i) the scheduler stays
    in COMPUTE and withholds the grant. Leaving COMPUTE, Set Grant picks the earliest registered
    deadline (wrap-around comparison, holder wins ties). No per-input arithmetic: that is the
    area it saves against LOEDF, paid for in grant latency.
    """

    preemptive = False
    tracks_arrivals = False

    def __init__(self, deadline: IntArray, bits: int) -> None:
        self._deadline = deadline
        self._bits = bits
        self._mask = (1 << bits) - 1
        self.reset()

    def reset(self) -> None:
        """Timer at 0, nothing registered."""
        self.absolute = np.zeros_like(self._deadline)
        self.registered = np.zeros(self._deadline.shape, dtype=bool)
        self.timer = np.zeros(self._deadline.shape[0], dtype=np.int64)
        self._loading = first_candidate(self.registered)

    def compute(self, cycle: Cycle) -> BoolArray | None:
        """Pick the next request to register; pause while there is one."""
        self._loading = first_candidate(cycle.request & ~self.registered)
        return self._loading >= 0

    def select(self, cycle: Cycle, rows: IntArray | None) -> IntArray:
        """Earliest registered deadline among candidates; the holder wins ties."""
        rows = np.arange(len(cycle.owner)) if rows is None else rows
        keys = holder_first(self.absolute[rows], cycle.owner[rows])
        return tree_least_modular(cycle.candidates[rows], keys, self._bits + 1)

    def commit(self, cycle: Cycle, selected: BoolArray, best: IntArray) -> None:
        """Register one deadline, forget completed messages, advance the timer."""
        rows = np.nonzero(self._loading >= 0)[0]
        index = self._loading[rows]
        self.absolute[rows, index] = (self.timer[rows] + self._deadline[rows, index]) & self._mask
        self.registered[rows, index] = True
        done = np.nonzero(cycle.complete)[0]
        self.registered[done, cycle.transfer[done]] = False
        self.timer = (self.timer + 1) & self._mask
