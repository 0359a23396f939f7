"""The schedulers' properties (issue 5), checked cycle by cycle from what is observable.

The monitor sees only the channel — requests, `tlast`, `ready` and the grant — plus the timing
constants, and derives priorities from the paper's definitions (arrival + D for EDF, d - t - c
for LST, the index for FP, recency for LRU). It never reads a model's registers, so it checks
the models and the hardware alike (vectorized over R replicates; HDL traces use R = 1).
"""

from __future__ import annotations

import numpy as np

from rfc.lib.schedulers.spec import Algorithm


class PropertyError(AssertionError):
    """A scheduler broke one of its properties; the message says where and how."""


def lowest(mask: np.ndarray) -> np.ndarray:
    index = np.argmax(mask, axis=1)
    return np.where(mask[np.arange(len(index)), index], index, -1)


class PropertyMonitor:
    """Check one algorithm's properties on R replicates, one cycle per `observe` call.

    Args:
        algorithm: The algorithm's rule to hold the grants to (None: only the generic ones).
        transfer: int[R, N] beats per message (LST's remaining time).
        deadline: int[R, N] relative deadlines.
    """

    def __init__(
        self, algorithm: Algorithm | None, transfer: np.ndarray, deadline: np.ndarray
    ) -> None:
        self.algorithm = algorithm
        self.transfer = np.asarray(transfer, dtype=np.int64)
        self.deadline = np.asarray(deadline, dtype=np.int64)
        self.batch, self.n = self.transfer.shape
        shape = (self.batch, self.n)
        self.cycle = 0
        self.rows = np.arange(self.batch)
        self.holder = np.full(self.batch, -1)
        self.active = np.zeros(shape, dtype=bool)
        self.arrived = np.zeros(shape, dtype=np.int64)
        self.left = np.zeros(shape, dtype=np.int64)
        self.registered = np.zeros(shape, dtype=bool)
        self.registered_at = np.zeros(shape, dtype=np.int64)
        self.waited = np.zeros(shape, dtype=np.int64)
        self.served = np.zeros(shape, dtype=bool)
        self.expected = np.full(self.batch, -1)
        self.previous_choice = np.full(self.batch, -1)
        self.counts = {"moves": 0, "grants": 0, "completions": 0}

    def _fail(self, rows: np.ndarray, what: str) -> None:
        row = int(rows[0])
        raise PropertyError(f"cycle {self.cycle}, replicate {row}: {what(row)}")

    def observe(
        self,
        request: np.ndarray,
        last: np.ndarray,
        grant: np.ndarray,
        ready: np.ndarray | None = None,
    ) -> None:
        """Check cycle `self.cycle` and advance."""
        rows = self.rows
        ready = np.ones(self.batch, dtype=bool) if ready is None else ready
        granted = grant >= 0
        g = np.maximum(grant, 0)
        new = request & ~self.active
        self.arrived[new] = self.cycle
        self.left = np.where(new, self.transfer, self.left)
        self.served &= ~new
        self.waited = np.where(new, 0, self.waited)
        self.active |= request

        bad = np.nonzero(granted & ~request[rows, g])[0]
        if bad.size:
            self._fail(bad, lambda r: f"grant to input {grant[r]} which does not request")
        bad = np.nonzero(granted & ~ready)[0]
        if bad.size:
            self._fail(bad, lambda r: f"grant to input {grant[r]} while the channel stalls")
        self._check_rule(request, grant, ready)

        self.counts["grants"] += int(granted.sum())
        complete = granted & last[rows, g]
        self.counts["completions"] += int(complete.sum())
        moved = np.nonzero(granted)[0]
        self.left[moved, grant[moved]] -= 1
        self.served[moved, grant[moved]] = True
        self.holder = np.where(granted, grant, self.holder)
        self.holder = np.where(complete, -1, self.holder)
        done = np.nonzero(complete)[0]
        waiting = self.active & ~self.served
        waiting[done, grant[done]] = False
        self.waited += waiting & complete[:, None]
        self.active[done, grant[done]] = False
        candidates = request.copy()
        candidates[done, grant[done]] = False
        self._advance_fixed_priority(candidates, complete, granted)
        self._register(request, complete, grant)
        self.cycle += 1

    def _check_rule(self, request: np.ndarray, grant: np.ndarray, ready: np.ndarray) -> None:
        algorithm = self.algorithm
        if algorithm is None:
            return
        granted = grant >= 0
        held = self.holder >= 0
        if not algorithm.preemptive:
            bad = np.nonzero(held & ready & (grant != self.holder))[0]
            if bad.size:
                self._fail(
                    bad,
                    lambda r: (
                        f"non-preemptive grant moved from {self.holder[r]} to {grant[r]} "
                        "before its tlast"
                    ),
                )
        if algorithm in (Algorithm.NPFP, Algorithm.PFP):
            expected = self.previous_choice if algorithm is Algorithm.PFP else self.expected
            bad = np.nonzero(granted & ~held & (grant != expected))[0]
            if algorithm is Algorithm.PFP:
                bad = np.nonzero(granted & (grant != expected))[0]
            if bad.size:
                self._fail(
                    bad,
                    lambda r: (
                        f"fixed priority granted {grant[r]}, but the lowest requesting "
                        f"index at the decision was {expected[r]}"
                    ),
                )
        if algorithm is Algorithm.LRU:
            late = self.waited > self.n - 1
            bad = np.nonzero(late.any(axis=1))[0]
            if bad.size:
                self._fail(
                    bad,
                    lambda r: (
                        f"input {int(np.argmax(late[r]))} waited "
                        f"{self.waited[r].max()} transfers (more than N-1 = {self.n - 1})"
                    ),
                )
        move = granted & held & (grant != self.holder)
        if algorithm.preemptive and move.any():
            self.counts["moves"] += int(move.sum())
            key = self._priority(request)
            rows = np.nonzero(move)[0]
            new_key, old_key = key[rows, grant[rows]], key[rows, self.holder[rows]]
            bad = rows[new_key >= old_key]
            if bad.size:
                self._fail(
                    bad,
                    lambda r: (
                        f"{algorithm.value} moved the grant from {self.holder[r]} "
                        f"(priority key {key[r, self.holder[r]]}) to {grant[r]} "
                        f"(key {key[r, grant[r]]}), which is not strictly more urgent"
                    ),
                )

    def _priority(self, request: np.ndarray) -> np.ndarray:
        """Smaller is more urgent: the algorithm's own rule, from observables only."""
        if self.algorithm is Algorithm.PFP:
            return np.broadcast_to(np.arange(self.n), (self.batch, self.n))
        if self.algorithm is Algorithm.LOEDF:
            return self.arrived + self.deadline
        if self.algorithm is Algorithm.ROEDF:
            return self.registered_at + self.deadline
        return self.arrived + self.deadline - self.cycle - self.left

    def _advance_fixed_priority(
        self, candidates: np.ndarray, complete: np.ndarray, granted: np.ndarray
    ) -> None:
        choice = lowest(candidates)
        self.previous_choice = choice
        free = (self.holder < 0) & (self.expected < 0)
        self.expected = np.where(granted & ~complete, -1, self.expected)
        self.expected = np.where(free | complete, choice, self.expected)

    def _register(self, request: np.ndarray, complete: np.ndarray, grant: np.ndarray) -> None:
        """ROEDF's documented registration: one waiting request per cycle, lowest index first."""
        pick = lowest(request & ~self.registered)
        rows = np.nonzero(pick >= 0)[0]
        self.registered[rows, pick[rows]] = True
        self.registered_at[rows, pick[rows]] = self.cycle
        done = np.nonzero(complete)[0]
        self.registered[done, grant[done]] = False
