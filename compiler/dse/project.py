"""A scheduler for one project: its publishers' traffic, simulated under every candidate.

The traffic follows DESIGN.md §7 with the project's own numbers: publisher i sends
``transfer_beats`` beats (from its message layout and the bus width), then stays idle for its
period minus its transfer, and must finish within its deadline (default: the period); all are
released at cycle 0, the worst case of simultaneous arrival. One run of
`simulation_cycles` cycles per candidate, with the counter widths the hardware would get.
Candidates are the six algorithms and, with two or more publishers, the two-level
combinations of the paper's most promising pair (LRU over LOEDF and LST halves).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from rfc.dse.kernel import METRICS, run_replicates
from rfc.dse.objective import Candidate, Criterion, rank, reasons
from rfc.dse.sweep import ALGORITHMS
from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.lib.schedulers.model import tree_of
from rfc.lib.schedulers.spec import AnySchedulerSpec, parse_scheduler

#: Shortest and longest simulation of a project, in cycles.
MIN_CYCLES, MAX_CYCLES = 10_000, 200_000
#: Periods of the slowest publisher simulated (within the bounds above).
PERIODS_SIMULATED = 20


@dataclass(frozen=True)
class ProjectTraffic:
    """The scheduler inputs of a project, in input order (= publisher id)."""

    publishers: tuple[str, ...]
    transfer: tuple[int, ...]
    period: tuple[int, ...]
    deadline: tuple[int, ...]

    @property
    def n(self) -> int:
        """Number of publishers."""
        return len(self.publishers)

    @property
    def idle(self) -> tuple[int, ...]:
        """F_i = period - T_i: the idle time after each message."""
        return tuple(p - t for p, t in zip(self.period, self.transfer, strict=True))

    @property
    def cycles(self) -> int:
        """Simulated cycles: `PERIODS_SIMULATED` periods of the slowest publisher, bounded."""
        return min(MAX_CYCLES, max(MIN_CYCLES, PERIODS_SIMULATED * max(self.period)))


def project_traffic(design: Design) -> ProjectTraffic:
    """The publishers' timing from the holistic model.

    Raises:
        RfcError: A publisher has no period (the DSE cannot simulate it), or none exists.
    """
    inputs = design.infrastructure.scheduler.inputs
    if not inputs:
        raise RfcError(f"project '{design.project.name}' has no publisher in the logic to schedule")
    missing = [i.publisher for i in inputs if i.period is None]
    if missing:
        raise RfcError(
            f"publisher{'s' if len(missing) > 1 else ''} {', '.join(missing)} of project "
            f"'{design.project.name}' {'have' if len(missing) > 1 else 'has'} no period; "
            "rfc dse needs the period (and optionally the deadline) of every publisher",
            hint="add 'period: 100 us' (and 'deadline: ...') to each publisher block",
        )
    for i in inputs:
        if i.period < i.transfer_beats:
            raise RfcError(
                f"publisher {i.publisher} sends {i.transfer_beats} beats every {i.period} cycles: "
                "its own messages already overload the channel",
                hint="lengthen its period or widen the bus",
            )
    return ProjectTraffic(
        tuple(i.publisher for i in inputs),
        tuple(i.transfer_beats for i in inputs),
        tuple(int(i.period) for i in inputs),
        tuple(int(i.deadline if i.deadline is not None else i.period) for i in inputs),
    )


def candidates(n: int) -> list[str]:
    """The six algorithms and, for two or more inputs, LRU over each pair of LOEDF/LST halves."""
    names = list(ALGORITHMS)
    if n >= 2:
        names += [f"LRU({a},{b})" for a, b in itertools.product(("LOEDF", "LST"), repeat=2)]
    return names


def spec_of(scheduler: str, traffic: ProjectTraffic) -> AnySchedulerSpec:
    """The scheduler as generated for the project (its T and D, default counter widths)."""
    return parse_scheduler(scheduler, traffic.n, list(traffic.transfer), list(traffic.deadline))


def evaluate(scheduler: str, traffic: ProjectTraffic) -> Candidate:
    """Simulate the project under `scheduler` and collect its metrics."""
    row = run_replicates(
        tree_of(spec_of(scheduler, traffic)),
        np.array([traffic.transfer]),
        np.array([traffic.idle]),
        np.array([traffic.deadline]),
        traffic.cycles,
    )[0]
    return Candidate(scheduler, dict(zip(METRICS, (float(v) for v in row), strict=True)))


@dataclass(frozen=True)
class Recommendation:
    """The ranking of the candidates for a project and why the first one wins."""

    traffic: ProjectTraffic
    objective: tuple[Criterion, ...]
    ranking: tuple[Candidate, ...]
    reasons: tuple[str, ...]

    @property
    def scheduler(self) -> str:
        """The recommended scheduler (an algorithm or a composition)."""
        return self.ranking[0].scheduler


def _resources(traffic: ProjectTraffic) -> Callable[[Candidate], dict[str, int]]:
    def synthesized(candidate: Candidate) -> dict[str, int]:
        from rfc.lib.schedulers.generate import synthesize

        report = synthesize(spec_of(candidate.scheduler, traffic))
        return {"lut": report.resources.lut, "ff": report.resources.ff}

    return synthesized


def recommend(
    design: Design,
    objective: Sequence[Criterion],
    names: Sequence[str] | None = None,
) -> Recommendation:
    """Rank `names` (default `candidates`) for the project's publishers by `objective`.

    Raises:
        RfcError: A publisher lacks the timing the simulation needs.
    """
    traffic = project_traffic(design)
    evaluated = [evaluate(name, traffic) for name in names or candidates(traffic.n)]
    ranking = rank(evaluated, objective, _resources(traffic))
    return Recommendation(
        traffic, tuple(objective), tuple(ranking), tuple(reasons(ranking, objective))
    )
