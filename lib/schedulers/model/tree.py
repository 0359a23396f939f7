"""A scheduler as the compiled kernels see it: a flat tree of statechart nodes and its constants.

A single algorithm is one node; `compose` puts a parent node over child trees (paper §7.2.5).
Nodes are stored in pre-order, per-input values side by side (see `kernels` for the layout).
Timing constants may differ per replicate, so they carry a leading batch axis R.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from rfc.lib.schedulers.model import kernels
from rfc.lib.schedulers.spec import Algorithm

BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]

#: Kernel code of each algorithm.
ALGORITHM_CODES = {algorithm: code for code, algorithm in enumerate(Algorithm)}


class Replicated:
    """R and N of a record whose `transfer` (like its other per-input arrays) is int[R, N]."""

    transfer: IntArray

    @property
    def replicates(self) -> int:
        """R: the replicates."""
        return int(self.transfer.shape[0])

    @property
    def n(self) -> int:
        """N: the inputs."""
        return int(self.transfer.shape[1])


@dataclass(frozen=True, eq=False)
class SchedulerTree(Replicated):
    """Structure and constants of a scheduler (one algorithm or a composition), on R replicates.

    Attributes:
        algorithm: int[K], kernel code of each node (pre-order: node 0 is the root).
        inputs: int[K], inputs of each node.
        base: int[K], index of each node's first input in the flat per-input arrays.
        leaf_start: int[K], a leaf's first scheduler input, -1 for a parent.
        parent: int[K], parent node, -1 for the root.
        slot: int[K], the node's input index in its parent.
        child_of: int[M], per flat input, the node feeding it, -1 at a leaf.
        bits: int[K], counter width of each node.
        node_transfer: int[R, M], per flat input, T (a parent's: its child's largest).
        node_deadline: int[R, M], per flat input, D (a parent's: its child's smallest).
        transfer: int[R, N], T of each scheduler input.
        deadline: int[R, N], D of each scheduler input.
    """

    algorithm: IntArray
    inputs: IntArray
    base: IntArray
    leaf_start: IntArray
    parent: IntArray
    slot: IntArray
    child_of: IntArray
    bits: IntArray
    node_transfer: IntArray
    node_deadline: IntArray
    transfer: IntArray
    deadline: IntArray

    @property
    def structure(self) -> tuple[IntArray, ...]:
        """The structure tuple the kernels take."""
        return (
            self.algorithm,
            self.inputs,
            self.base,
            self.leaf_start,
            self.parent,
            self.slot,
            self.child_of,
            self.bits,
        )

    def load(self) -> IntArray:
        """int[R, M]: the value each per-input key loads on arrival (see `kernels.counter_load`)."""
        loads = np.empty_like(self.node_deadline)
        for k, code in enumerate(self.algorithm):
            part = slice(self.base[k], self.base[k] + self.inputs[k])
            half = 1 << (int(self.bits[k]) - 1)
            t, d = self.node_transfer[:, part], self.node_deadline[:, part]
            if code == kernels.LOEDF:
                loads[:, part] = d - 1 + half
            elif code == kernels.LST:
                loads[:, part] = d - t - 1 + half
            else:
                loads[:, part] = d
        return loads


def _ints(values: Sequence[int] | IntArray) -> IntArray:
    return np.asarray(values, dtype=np.int64)


def leaf(algorithm: Algorithm, transfer: IntArray, deadline: IntArray, bits: int) -> SchedulerTree:
    """A one-node tree: `algorithm` over N inputs with T, D of shape [R, N]."""
    n = transfer.shape[1]
    return SchedulerTree(
        algorithm=_ints([ALGORITHM_CODES[algorithm]]),
        inputs=_ints([n]),
        base=_ints([0]),
        leaf_start=_ints([0]),
        parent=_ints([-1]),
        slot=_ints([0]),
        child_of=np.full(n, -1, dtype=np.int64),
        bits=_ints([bits]),
        node_transfer=transfer,
        node_deadline=deadline,
        transfer=transfer,
        deadline=deadline,
    )


def compose(parent: SchedulerTree, children: Sequence[SchedulerTree]) -> SchedulerTree:
    """Put the one-node tree `parent` (one input per child) over the `children` trees."""
    node_offsets, flat_offsets, leaf_offsets = [], [], []
    node, flat, first_leaf = 1, len(children), 0
    for child in children:
        node_offsets.append(node)
        flat_offsets.append(flat)
        leaf_offsets.append(first_leaf)
        node += len(child.algorithm)
        flat += len(child.child_of)
        first_leaf += child.n
    pairs = list(zip(children, node_offsets, strict=True))

    def shifted(values: IntArray, offset: int) -> IntArray:
        return np.where(values >= 0, values + offset, values)

    def side_by_side(field: str) -> IntArray:
        return np.concatenate(
            [getattr(parent, field), *(getattr(c, field) for c in children)], axis=-1
        )

    return SchedulerTree(
        algorithm=side_by_side("algorithm"),
        inputs=np.concatenate([_ints([len(children)]), *(c.inputs for c in children)]),
        base=np.concatenate(
            [_ints([0]), *(c.base + f for c, f in zip(children, flat_offsets, strict=True))]
        ),
        leaf_start=np.concatenate(
            [
                _ints([-1]),
                *(shifted(c.leaf_start, f) for c, f in zip(children, leaf_offsets, strict=True)),
            ]
        ),
        parent=np.concatenate(
            [_ints([-1]), *(np.where(c.parent >= 0, c.parent + k, 0) for c, k in pairs)]
        ),
        slot=np.concatenate(
            [_ints([0]), *(np.where(c.parent >= 0, c.slot, i) for i, c in enumerate(children))]
        ),
        child_of=np.concatenate([_ints(node_offsets), *(shifted(c.child_of, k) for c, k in pairs)]),
        bits=side_by_side("bits"),
        node_transfer=side_by_side("node_transfer"),
        node_deadline=side_by_side("node_deadline"),
        transfer=np.concatenate([c.transfer for c in children], axis=1),
        deadline=np.concatenate([c.deadline for c in children], axis=1),
    )
