"""The paper's sweep: every scheduler at every N on every dataset, and Figure 14's combinations.

`plan` lists the points, `run_sweep` simulates them (in parallel, with progress) and adds the
LUT/FF of each algorithm at each N from the scheduler synthesis (cached).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from rfc.dse.datasets import SIZES, Dataset, Traffic, dataset, draw
from rfc.dse.engine import Task, TasksFailedError, chunks, counter_bits, run_tasks
from rfc.dse.kernel import COLUMN, METRICS
from rfc.dse.metrics import Summary, summarize
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec

#: The six algorithms, in the paper's order.
ALGORITHMS = tuple(a.value for a in Algorithm)
#: Figure 14: one scheduler of two halves of N inputs under LRU, alike or mixed (paper §7.2.5).
COMBINATIONS = ("LRU(LOEDF,LOEDF)", "LRU(LST,LST)", "LRU(LOEDF,LST)")


@dataclass(frozen=True)
class Plan:
    """What to simulate.

    Attributes:
        datasets: Dataset names.
        sizes: Numbers of accelerators N.
        replicates: Replicates per point (None: each dataset's own, 200 or 10).
        combinations: Also run `COMBINATIONS` on the first dataset at the largest N.
        seed: Seed of the traffic.
    """

    datasets: tuple[str, ...] = ("large", "cc1", "cc2", "cc3", "cc4")
    sizes: tuple[int, ...] = SIZES
    replicates: int | None = None
    combinations: bool = True
    seed: int = 0

    def replicates_of(self, data: Dataset) -> int:
        """Replicates per point of `data`."""
        return self.replicates if self.replicates is not None else data.replicates


@dataclass(frozen=True)
class Point:
    """The result of one point: every replicate's metrics row, summarized on demand.

    Attributes:
        dataset: Dataset name.
        scheduler: Algorithm or composition (``LRU(LOEDF,LST)``).
        n: Accelerators.
        cycles: Simulated cycles per replicate.
        counter_bits: Counter width the schedulers were given.
        rows: float[R, len(METRICS)].
    """

    dataset: str
    scheduler: str
    n: int
    cycles: int
    counter_bits: int
    rows: npt.NDArray[np.float64] = field(repr=False)

    @property
    def replicates(self) -> int:
        """R."""
        return int(self.rows.shape[0])

    def summary(self, metric: str) -> Summary:
        """Mean and 95 % confidence interval of `metric` over the replicates."""
        return summarize(self.rows[:, COLUMN[metric]])

    def as_dict(self) -> dict[str, object]:
        """JSON-friendly form with every metric summarized."""
        return {
            "dataset": self.dataset,
            "scheduler": self.scheduler,
            "n": self.n,
            "replicates": self.replicates,
            "cycles": self.cycles,
            "counter_bits": self.counter_bits,
            "metrics": {name: self.summary(name).as_dict() for name in METRICS},
        }


@dataclass(frozen=True)
class Resources:
    """LUT and FF of one algorithm at N inputs (T = 100, D = 200: the synthesis sweep's)."""

    algorithm: str
    n: int
    lut: int
    ff: int


@dataclass(frozen=True)
class SweepResult:
    """Every point of a plan, and the resources of each algorithm at each N.

    Attributes:
        failures: Tasks that raised on a cluster (their points are left out), as
            "scheduler N=.. dataset replicates a-b: error".
    """

    plan: Plan
    points: tuple[Point, ...]
    resources: tuple[Resources, ...]
    failures: tuple[str, ...] = ()

    def point(self, dataset_name: str, scheduler: str, n: int) -> Point | None:
        """The point simulated for these, if any."""
        for point in self.points:
            if (point.dataset, point.scheduler, point.n) == (dataset_name, scheduler, n):
                return point
        return None


def _traffic(plan: Plan) -> dict[tuple[str, int], tuple[Traffic, int]]:
    traffic = {}
    for name in plan.datasets:
        data = dataset(name)
        for n in plan.sizes:
            drawn = draw(data, n, plan.replicates_of(data), plan.seed)
            traffic[name, n] = drawn, data.cycles
    return traffic


def tasks_of(plan: Plan) -> tuple[list[Task], dict[tuple[str, str, int], tuple[int, int]]]:
    """The tasks of a plan and, per point key, its (cycles, counter bits)."""
    tasks, info = [], {}
    traffic = _traffic(plan)
    for (name, n), (drawn, cycles) in traffic.items():
        bits = counter_bits(drawn, cycles)
        schedulers = list(ALGORITHMS)
        if plan.combinations and name == plan.datasets[0] and n == max(plan.sizes) and n >= 2:
            schedulers += COMBINATIONS
        for scheduler in schedulers:
            key = (name, scheduler, n)
            info[key] = cycles, bits
            tasks += chunks(key, scheduler, drawn, cycles)
    return tasks, info


def synthesized_resources(sizes: Sequence[int], jobs: int) -> tuple[Resources, ...]:
    """LUT/FF of the six algorithms at each N, from the (cached) scheduler synthesis."""
    from rfc.lib.schedulers.generate import synthesize

    points = [(algorithm, n) for n in sizes for algorithm in ALGORITHMS]

    def one(point: tuple[str, int]) -> Resources:
        report = synthesize(SchedulerSpec.create(*point))
        return Resources(point[0], point[1], report.resources.lut, report.resources.ff)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return tuple(pool.map(one, points))


def run_sweep(
    plan: Plan,
    jobs: int,
    *,
    synthesis: bool = True,
    advance: Callable[[float], None] | None = None,
    cluster: str | None = None,
) -> SweepResult:
    """Simulate every point of `plan` on `jobs` processes (or a Dask cluster), then resources.

    On a cluster, the points whose tasks failed are left out and named in `failures`.
    """
    tasks, info = tasks_of(plan)
    failures: tuple[str, ...] = ()
    try:
        rows = run_tasks(tasks, jobs, advance, cluster)
    except TasksFailedError as failed:
        rows, failures = failed.rows, tuple(failed.failures)
    points = tuple(
        Point(name, scheduler, n, *info[name, scheduler, n], rows[name, scheduler, n])
        for (name, scheduler, n) in info
        if (name, scheduler, n) in rows
    )
    resources = synthesized_resources(plan.sizes, jobs) if synthesis else ()
    return SweepResult(plan, points, resources, failures)
