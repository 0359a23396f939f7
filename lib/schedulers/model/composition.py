"""The model of a composed scheduler: a parent arbitrating between child schedulers.

Child c offers the channel to one of its inputs (its proposal); the parent sees input c
requesting while child c offers, with that input's `tlast`; the parent's grant of c is the
`ready` of child c. The grant of the composite is the offered input of the granted child.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Protocol

import numpy as np

from rfc.lib.schedulers.model.statechart import BoolArray, IntArray


class SchedulerModel(Protocol):
    """What every scheduler model offers (single algorithms and compositions alike).

    Attributes:
        n: Number of inputs.
        batch: Number of replicates R.
        transfer: int[R, N] transfer times T_i.
        deadline: int[R, N] relative deadlines D_i.
    """

    n: int
    batch: int
    transfer: IntArray
    deadline: IntArray

    def reset(self) -> None:
        """Synchronous reset."""

    def proposal(self, request: BoolArray) -> IntArray:
        """int[R]: the input offered the channel this cycle, or -1."""

    def grant(self, request: BoolArray, ready: BoolArray | None = None) -> IntArray:
        """int[R]: the input granted this cycle, or -1."""

    def step(self, request: BoolArray, last: BoolArray, ready: BoolArray | None = None) -> IntArray:
        """One clock cycle; returns this cycle's grant."""


class CompositionModel:
    """A scheduler whose inputs are schedulers, on R replicates.

    Args:
        parent: Model with one input per child.
        children: Models whose inputs, side by side, are the composite's.
    """

    def __init__(self, parent: SchedulerModel, children: Sequence[SchedulerModel]) -> None:
        if parent.n != len(children):
            raise ValueError(f"the parent has {parent.n} inputs for {len(children)} children")
        self.parent = parent
        self.children = tuple(children)
        self.batch = parent.batch
        self.n = sum(child.n for child in children)
        self.transfer = np.concatenate([child.transfer for child in children], axis=1)
        self.deadline = np.concatenate([child.deadline for child in children], axis=1)
        starts = np.cumsum([0] + [child.n for child in children])
        self._slices = [slice(a, b) for a, b in itertools.pairwise(starts)]
        self._rows = np.arange(self.batch)

    def reset(self) -> None:
        """Reset the parent and every child."""
        self.parent.reset()
        for child in self.children:
            child.reset()

    def _offers(self, request: BoolArray) -> list[IntArray]:
        pairs = zip(self.children, self._slices, strict=True)
        return [child.proposal(request[:, part]) for child, part in pairs]

    def _combine(self, chosen: IntArray, offers: list[IntArray]) -> IntArray:
        grant = np.full(self.batch, -1, dtype=np.int64)
        for c, (offer, part) in enumerate(zip(offers, self._slices, strict=True)):
            grant = np.where(chosen == c, offer + part.start, grant)
        return grant

    def proposal(self, request: BoolArray) -> IntArray:
        """int[R]: the input offered by the child the parent offers the channel to, or -1."""
        offers = self._offers(request)
        return self._combine(self.parent.proposal(np.stack([o >= 0 for o in offers], 1)), offers)

    def grant(self, request: BoolArray, ready: BoolArray | None = None) -> IntArray:
        """int[R]: the granted input of the composite, or -1."""
        offered = self.proposal(request)
        return offered if ready is None else np.where(ready, offered, -1)

    def step(self, request: BoolArray, last: BoolArray, ready: BoolArray | None = None) -> IntArray:
        """One clock cycle of parent and children; returns this cycle's grant."""
        offers = self._offers(request)
        child_request = np.stack([offer >= 0 for offer in offers], axis=1)
        child_last = np.stack(
            [
                (offer >= 0) & last[:, part][self._rows, np.maximum(offer, 0)]
                for offer, part in zip(offers, self._slices, strict=True)
            ],
            axis=1,
        )
        chosen = self.parent.step(child_request, child_last, ready)
        for c, (child, part) in enumerate(zip(self.children, self._slices, strict=True)):
            child.step(request[:, part], last[:, part], chosen == c)
        return self._combine(chosen, offers)
