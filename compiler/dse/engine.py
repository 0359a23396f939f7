"""Run DSE points — a scheduler, N accelerators, a dataset — over replicates, in parallel.

A point's replicates run in the compiled kernel (`rfc.dse.kernel`), in chunks spread over
`jobs` processes; each chunk returns only its rows of metrics, so memory stays flat whatever
the sweep's size. The schedulers' counters are widened so that no counter saturates or wraps
during the run (`counter_bits`): the metrics then follow the paper's definitions exactly, and
`--verify-hdl` generates the hardware with the same widths.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from rfc.dse.datasets import Traffic
from rfc.dse.kernel import run_replicates
from rfc.lib.schedulers.model import compose_models, make_model
from rfc.lib.schedulers.model.scheduler import SchedulerModel
from rfc.lib.schedulers.model.tree import SchedulerTree
from rfc.lib.schedulers.spec import (
    AnySchedulerSpec,
    CompositionSpec,
    SchedulerSpec,
    default_counter_bits,
    parse_scheduler,
)

#: A point of a sweep: (dataset, scheduler, N).
PointKey = tuple[str, str, int]

#: Replicates per task handed to a worker process.
CHUNK = 25


def counter_bits(traffic: Traffic, cycles: int) -> int:
    """Counter width that stays exact for `cycles` cycles: no saturation, no wrap-around.

    LOEDF/LST counters saturate once a message is 2^(bits-1) - D cycles late, and ROEDF's
    circle compares deadlines exactly while they lie within 2^(bits-1) of each other; a run of
    `cycles` cycles needs 2^(bits-1) > cycles + max(T + D).
    """
    largest_t, largest_d = int(traffic.transfer.max()), int(traffic.deadline.max())
    horizon = cycles + largest_t + largest_d
    return max(default_counter_bits([largest_t], [largest_d]), horizon.bit_length() + 1)


def structure(scheduler: str, n: int) -> AnySchedulerSpec:
    """The shape of `scheduler` (``LOEDF``, ``LRU(LOEDF,LST)``) on `n` inputs, timing aside."""
    return parse_scheduler(scheduler, n, transfer=1, deadline=2)


def build_tree(shape: AnySchedulerSpec, traffic: Traffic, bits: int) -> SchedulerTree:
    """The scheduler `shape` with the per-replicate timing of `traffic` and `bits`-wide counters."""

    def model(part: AnySchedulerSpec, start: int) -> SchedulerModel:
        if isinstance(part, SchedulerSpec):
            stop = start + part.n
            return make_model(
                part.algorithm,
                part.n,
                traffic.transfer[:, start:stop],
                traffic.deadline[:, start:stop],
                batch=traffic.replicates,
                counter_bits=bits,
            )
        assert isinstance(part, CompositionSpec)
        children = [
            model(child, start + offset)
            for child, offset in zip(part.children, part.offsets, strict=True)
        ]
        return compose_models(part.parent.algorithm, children, counter_bits=bits)

    tree: SchedulerTree = model(shape, 0).tree
    return tree


def simulate(scheduler: str, traffic: Traffic, cycles: int) -> npt.NDArray[np.float64]:
    """float[R, len(METRICS)]: the metrics of every replicate of `traffic` under `scheduler`."""
    shape = structure(scheduler, traffic.n)
    tree = build_tree(shape, traffic, counter_bits(traffic, cycles))
    return run_replicates(tree, traffic.transfer, traffic.idle, traffic.deadline, cycles)


@dataclass(frozen=True)
class Task:
    """A chunk of one point's replicates: `key` names the point, `part` orders its chunks."""

    key: PointKey
    part: int
    scheduler: str
    traffic: Traffic
    cycles: int

    @property
    def work(self) -> float:
        """Relative cost, for the progress bar (a cycle costs more with many inputs)."""
        return self.traffic.replicates * self.cycles * (1 + self.traffic.n / 64)


def _run(task: Task) -> npt.NDArray[np.float64]:
    return simulate(task.scheduler, task.traffic, task.cycles)


def chunks(key: PointKey, scheduler: str, traffic: Traffic, cycles: int) -> list[Task]:
    """Split a point into tasks of at most `CHUNK` replicates."""
    tasks = []
    for part, start in enumerate(range(0, traffic.replicates, CHUNK)):
        rows = slice(start, start + CHUNK)
        sliced = Traffic(traffic.transfer[rows], traffic.idle[rows], traffic.deadline[rows])
        tasks.append(Task(key, part, scheduler, sliced, cycles))
    return tasks


def run_tasks(
    tasks: Sequence[Task],
    jobs: int,
    advance: Callable[[float], None] | None = None,
    cluster: str | None = None,
) -> dict[PointKey, npt.NDArray[np.float64]]:
    """Run tasks on `jobs` processes and join each point's rows in replicate order.

    Args:
        tasks: The chunks to run.
        jobs: Worker processes (1: in this process).
        advance: Called with each finished task's share of the work (for a progress bar).
        cluster: A Dask scheduler's address: run the tasks there instead.

    Raises:
        TasksFailedError: Some tasks raised on the cluster (it holds the others' points).
    """
    if cluster is not None:
        return _on_cluster(tasks, cluster, advance)
    total = sum(task.work for task in tasks) or 1.0
    rows: dict[PointKey, dict[int, npt.NDArray[np.float64]]] = {task.key: {} for task in tasks}

    def finished(task: Task, result: npt.NDArray[np.float64]) -> None:
        rows[task.key][task.part] = result
        if advance is not None:
            advance(task.work / total)

    if jobs <= 1:
        for task in tasks:
            finished(task, _run(task))
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            longest_first = sorted(tasks, key=lambda task: -task.work)
            futures = {pool.submit(_run, task): task for task in longest_first}
            for future in as_completed(futures):
                finished(futures[future], future.result())
    return {key: np.concatenate([parts[i] for i in sorted(parts)]) for key, parts in rows.items()}


def load_kernels() -> None:
    """Compile the kernels into numba's cache, or load them from it, on one tiny replicate.

    Called before the sweep: worker processes forked afterwards inherit them loaded instead of
    each loading them again (which costs more than a small sweep's simulation).
    """
    from rfc.dse.datasets import DATASETS, draw

    simulate("LRU", draw(DATASETS["cc1"], 2, 1), 10)


class TasksFailedError(Exception):
    """Tasks that raised on a cluster, and the points whose tasks all completed."""

    def __init__(self, failures: list[str], rows: dict[PointKey, npt.NDArray[np.float64]]) -> None:
        super().__init__("; ".join(failures))
        self.failures = failures
        self.rows = rows


def describe(task: Task) -> str:
    """A task's parameters, as `rfc dse` names them."""
    dataset, scheduler, n = task.key
    first = task.part * CHUNK
    last = first + task.traffic.replicates - 1
    return f"{scheduler} N={n} {dataset} replicates {first}-{last}"


def _on_cluster(
    tasks: Sequence[Task], address: str, advance: Callable[[float], None] | None
) -> dict[PointKey, npt.NDArray[np.float64]]:
    from rfc.cluster import run_jobs

    total = sum(task.work for task in tasks) or 1.0

    def finished(task: Task, _: object) -> None:
        if advance is not None:
            advance(task.work / total)

    results, failures = run_jobs(_run, tasks, describe, address=address, finished=finished)
    failed = {task.key for task, result in zip(tasks, results, strict=True) if result is None}
    rows: dict[PointKey, dict[int, npt.NDArray[np.float64]]] = {}
    for task, result in zip(tasks, results, strict=True):
        if task.key not in failed and result is not None:
            rows.setdefault(task.key, {})[task.part] = result
    joined = {key: np.concatenate([p[i] for i in sorted(p)]) for key, p in rows.items()}
    if failures:
        raise TasksFailedError([str(f) for f in failures], joined)
    return joined


def default_jobs() -> int:
    """Worker processes when none are asked for: one per core this process may use."""
    return max(1, len(os.sched_getaffinity(0)))
