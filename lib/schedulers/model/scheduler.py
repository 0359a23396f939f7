"""The model class: R replicates of one scheduler, stepped one clock cycle per call.

A thin wrapper around the compiled kernels (`kernels`): it owns the state arrays and hands them
to `kernels.step_batch`, so the co-simulation reference and the DSE run the very same code.
"""

from __future__ import annotations

import numpy as np

from rfc.lib.schedulers.model import kernels
from rfc.lib.schedulers.model.tree import BoolArray, IntArray, SchedulerTree


class SchedulerModel:
    """One scheduler (an algorithm or a composition) on R replicates: `step` is one clock cycle.

    Args:
        tree: The scheduler's structure and timing constants.

    Attributes:
        n: Number of inputs.
        batch: Number of replicates R.
        transfer: int[R, N] transfer times T_i.
        deadline: int[R, N] relative deadlines D_i.
    """

    def __init__(self, tree: SchedulerTree) -> None:
        self.tree = tree
        self.n = tree.n
        self.batch = tree.replicates
        self.transfer = tree.transfer
        self.deadline = tree.deadline
        self._structure = tree.structure
        self._load = tree.load()
        nodes, flat = len(tree.algorithm), len(tree.child_of)
        self._state = (
            np.full((self.batch, nodes), -1, dtype=np.int64),
            np.zeros((self.batch, nodes), dtype=np.bool_),
            np.zeros((self.batch, nodes), dtype=np.int64),
            np.zeros((self.batch, flat), dtype=np.bool_),
            np.zeros((self.batch, flat), dtype=np.int64),
            np.zeros((self.batch, flat), dtype=np.bool_),
        )
        self._work, self._scratch = kernels.work_arrays(nodes, flat, int(tree.inputs.max()))
        self._always = np.ones(self.batch, dtype=np.bool_)
        self.reset()

    def reset(self) -> None:
        """Synchronous reset: no holder, RUN state, empty arrival history, reset tables."""
        kernels.reset_batch(self._structure, self._state)

    def _inputs(self, signal: BoolArray) -> BoolArray:
        return np.ascontiguousarray(signal, dtype=np.bool_).reshape(self.batch, self.n)

    def proposal(self, request: BoolArray) -> IntArray:
        """int[R]: the input offered the channel this cycle (before `ready`), or -1."""
        offered = np.empty(self.batch, dtype=np.int64)
        kernels.offer_batch(
            self._structure, self._state, self._inputs(request), offered, self._work
        )
        return offered

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
        grant = np.empty(self.batch, dtype=np.int64)
        accepts = self._always if ready is None else np.ascontiguousarray(ready, dtype=np.bool_)
        kernels.step_batch(
            self._structure,
            self._load,
            self.tree.node_deadline,
            self._state,
            self._inputs(request),
            self._inputs(last),
            accepts,
            grant,
            self._work,
            self._scratch,
        )
        return grant
