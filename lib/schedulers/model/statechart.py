"""The cycle-exact model of the statechart skeleton, vectorized over a batch of replicates.

Every array has a leading batch dimension R (independent replicates simulated in lock-step) and,
where it is per input, a second dimension N. One call to `clock` is one rising clock edge of the
hardware in `rfc.lib.schedulers.statechart`; the register-transfer description it follows is in
docs/schedulers.md ("Cycle semantics"), and the co-simulation tests hold both to it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt

BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]


@dataclass
class Cycle:
    """The combinational values of one cycle that a policy's Compute Condition may read.

    Attributes:
        request: bool[R, N], the inputs' `tvalid`.
        candidates: bool[R, N], requesters that may be granted next (the completing one excluded).
        transfer: int[R], the input whose beat moves this cycle, or -1.
        complete: bool[R], a `tlast` beat moves this cycle.
        owner: int[R], the holder (kept through a ROEDF pause), or -1.
        pending: bool[R, N] or None, inputs with a message in progress (arrival tracking only).
        arrival: bool[R, N] or None, messages that arrive this cycle (arrival tracking only).
    """

    request: BoolArray
    candidates: BoolArray
    transfer: IntArray
    complete: BoolArray
    owner: IntArray
    pending: BoolArray | None
    arrival: BoolArray | None


class Policy(Protocol):
    """The algorithm-specific parts of the statechart: Compute Condition and Set Grant.

    Attributes:
        preemptive: Set Grant re-decides on every cycle (not only when idle or at `tlast`).
        tracks_arrivals: The skeleton must tell new messages apart (`Cycle.arrival`).
    """

    preemptive: bool
    tracks_arrivals: bool

    def reset(self) -> None:
        """Put the priority table in its reset state."""

    def compute(self, cycle: Cycle) -> BoolArray | None:
        """Compute Condition: prepare this cycle's priorities; return rows that must pause.

        Returns:
            bool[R] of replicates that enter (or stay in) the COMPUTE state, or None if the
            algorithm never pauses.
        """

    def select(self, cycle: Cycle, rows: IntArray | None) -> IntArray:
        """Set Grant: the highest-priority candidate of each replicate in `rows`, or -1.

        Args:
            cycle: This cycle's values.
            rows: The replicates that re-decide (None: all of them).
        """

    def commit(self, cycle: Cycle, selected: BoolArray, best: IntArray) -> None:
        """Clock edge of the priority table (`selected` marks rows that took `best`)."""


class StatechartModel:
    """One scheduler algorithm on R replicates: `step` is one clock cycle of the hardware.

    Args:
        policy: The algorithm's Compute Condition and Set Grant parts.
        n: Number of inputs.
        batch: Number of replicates R.
        transfer: int[R, N] transfer times the policy was built with (kept for composition).
        deadline: int[R, N] deadlines the policy was built with (kept for composition).
    """

    def __init__(
        self,
        policy: Policy,
        n: int,
        batch: int,
        transfer: IntArray,
        deadline: IntArray,
    ) -> None:
        self.policy = policy
        self.n = n
        self.batch = batch
        self.transfer = transfer
        self.deadline = deadline
        self._rows = np.arange(batch)
        self.reset()

    def reset(self) -> None:
        """Synchronous reset: no holder, RUN state, empty arrival history, reset table."""
        self._owner = np.full(self.batch, -1, dtype=np.int64)
        self._computing = np.zeros(self.batch, dtype=bool)
        self._seen = np.zeros((self.batch, self.n), dtype=bool)
        self.policy.reset()

    @property
    def owner(self) -> IntArray:
        """int[R]: the registered holder (granted when it requests, outside a pause), or -1."""
        return self._owner.copy()

    def proposal(self, request: BoolArray) -> IntArray:
        """int[R]: the input offered the channel this cycle (before `ready`), or -1."""
        owner = self._owner
        live = (owner >= 0) & ~self._computing
        offered = live & request[self._rows, np.maximum(owner, 0)]
        return np.where(offered, owner, -1)

    def grant(self, request: BoolArray, ready: BoolArray | None = None) -> IntArray:
        """int[R]: the granted input this cycle (drives its `tready`), or -1."""
        offered = self.proposal(request)
        return offered if ready is None else np.where(ready, offered, -1)

    def step(self, request: BoolArray, last: BoolArray, ready: BoolArray | None = None) -> IntArray:
        """Advance one cycle and return this cycle's grant.

        Args:
            request: bool[R, N], `tvalid` of every input.
            last: bool[R, N], `tlast` of every input.
            ready: bool[R], the channel accepts a beat (None: always).

        Returns:
            int[R], the input granted on this cycle, -1 for none.
        """
        grant = self.grant(request, ready)
        self._clock(request, last, grant)
        return grant

    def _clock(self, request: BoolArray, last: BoolArray, grant: IntArray) -> None:
        rows = self._rows
        moving = grant >= 0
        complete = moving & last[rows, np.maximum(grant, 0)]
        candidates = request.copy()
        candidates[rows[complete], grant[complete]] = False
        pending = arrival = None
        if self.policy.tracks_arrivals:
            pending = request | self._seen
            arrival = request & ~self._seen
            self._seen = pending.copy()
            self._seen[rows[complete], grant[complete]] = False
        cycle = Cycle(request, candidates, grant, complete, self._owner, pending, arrival)
        pause = self.policy.compute(cycle)
        reselect = self._computing | complete | (self._owner < 0)
        if self.policy.preemptive:
            reselect = np.ones_like(reselect)
        if pause is not None:
            reselect &= ~pause
        if self.policy.preemptive and pause is None:
            best = self.policy.select(cycle, None)
            owner = best
        else:
            deciding = np.nonzero(reselect)[0]
            best = np.full(self.batch, -1, dtype=np.int64)
            if deciding.size:
                best[deciding] = self.policy.select(cycle, deciding)
            owner = np.where(reselect, best, self._owner)
        self.policy.commit(cycle, reselect, best)
        if pause is not None:
            owner = np.where(pause & complete, -1, owner)
            self._computing = pause
        self._owner = owner
