"""Cycle-exact, vectorized models of the schedulers: the co-simulation reference and DSE engine.

A model simulates R independent replicates at once. Per clock cycle::

    model = make_model("LOEDF", n=8, transfer=T, deadline=D, batch=R)   # T, D: [N] or [R, N]
    grant = model.step(request, last)            # bool[R, N] each; returns int[R], -1 = none

`step` gives the same grant on the same cycle as the generated hardware (R = 1 is the
co-simulation reference). `ready` (bool[R]) models a channel that stalls. Compositions are
models too (`compose_models`, or `model_of` a `CompositionSpec`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from rfc.errors import RfcError
from rfc.lib.schedulers.model import tree
from rfc.lib.schedulers.model.scheduler import SchedulerModel
from rfc.lib.schedulers.spec import (
    DEFAULT_IDLE,
    DEFAULT_TRANSFER,
    Algorithm,
    AnySchedulerSpec,
    CompositionSpec,
    SchedulerSpec,
    check_inputs,
    counter_bits_for,
    parse_algorithm,
)

__all__ = [
    "SchedulerModel",
    "compose_models",
    "make_model",
    "model_of",
    "tree_of",
]

ArrayLike = int | Sequence[int] | npt.NDArray[np.integer]


def _timing(value: ArrayLike, n: int, batch: int, name: str) -> npt.NDArray[np.int64]:
    array = np.asarray(value, dtype=np.int64)
    try:
        array = np.broadcast_to(array, (batch, n)).copy()
    except ValueError:
        raise RfcError(
            f"{name} has shape {array.shape}; expected a scalar, [N] = [{n}] or "
            f"[R, N] = [{batch}, {n}]"
        ) from None
    if array.size and array.min() < 1:
        raise RfcError(f"{name} must be at least 1 cycle, got {array.min()}")
    return array


def make_model(
    algorithm: str | Algorithm,
    n: int,
    transfer: ArrayLike = DEFAULT_TRANSFER,
    deadline: ArrayLike | None = None,
    *,
    batch: int = 1,
    counter_bits: int | None = None,
) -> SchedulerModel:
    """Build the model of one scheduler on `batch` replicates.

    Args:
        algorithm: One of LRU, NPFP, PFP, ROEDF, LOEDF, LST (any case).
        n: Number of inputs.
        transfer: T_i in beats: a scalar, [N], or [R, N] (per replicate).
        deadline: D_i in cycles, shaped likewise; by default T_i + 100.
        batch: Number of replicates R.
        counter_bits: Width of the deadline/slack counters (as in the hardware); by default the
            width `SchedulerSpec.create` would choose for the largest values.

    Raises:
        RfcError: Unknown algorithm, or timing values out of range.
    """
    chosen = parse_algorithm(algorithm)
    check_inputs(n)
    transfers = _timing(transfer, n, batch, "the transfer time")
    if deadline is None:
        deadline = transfers + DEFAULT_IDLE
    deadlines = _timing(deadline, n, batch, "the deadline")
    return SchedulerModel(_leaf(chosen, transfers, deadlines, counter_bits))


def _leaf(
    algorithm: Algorithm,
    transfers: tree.IntArray,
    deadlines: tree.IntArray,
    counter_bits: int | None,
) -> tree.SchedulerTree:
    """The kernels' view of one scheduler on checked [R, N] timing (counters as `make_model`)."""
    flat_t, flat_d = [int(transfers.max())], [int(deadlines.max())]
    bits = counter_bits_for(flat_t, flat_d, counter_bits)
    return tree.leaf(algorithm, transfers, deadlines, bits)


def compose_models(
    parent: str | Algorithm,
    children: Sequence[SchedulerModel],
    *,
    counter_bits: int | None = None,
) -> SchedulerModel:
    """Compose child models under a `parent` algorithm (as `CompositionSpec.create` does).

    The parent's T and D for child c are, per replicate, the child's largest T and smallest D.
    """
    if len(children) < 2:
        raise RfcError(f"a composition needs at least two schedulers, got {len(children)}")
    transfer = np.stack([child.transfer.max(axis=1) for child in children], axis=1)
    deadline = np.stack([child.deadline.min(axis=1) for child in children], axis=1)
    top = _leaf(parse_algorithm(parent), transfer, deadline, counter_bits)
    return SchedulerModel(tree.compose(top, [child.tree for child in children]))


def model_of(spec: AnySchedulerSpec, batch: int = 1) -> SchedulerModel:
    """The model of a generated scheduler (or composition), with its exact constants."""
    return SchedulerModel(tree_of(spec, batch))


def tree_of(spec: AnySchedulerSpec, batch: int = 1) -> tree.SchedulerTree:
    """The compiled kernels' view of a generated scheduler (or composition) on R replicates."""
    if isinstance(spec, CompositionSpec):
        children = [tree_of(child, batch) for child in spec.children]
        return tree.compose(tree_of(spec.parent, batch), children)
    assert isinstance(spec, SchedulerSpec)
    transfers = _timing(spec.transfer, spec.n, batch, "the transfer time")
    deadlines = _timing(spec.deadline, spec.n, batch, "the deadline")
    return _leaf(spec.algorithm, transfers, deadlines, spec.counter_bits)
