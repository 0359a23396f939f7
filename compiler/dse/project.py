"""A scheduler for one project: its publishers' traffic, simulated under every candidate.

The traffic follows the paper's §7.2 (docs/dse.md) with the project's own numbers: publisher
i sends ``transfer_beats`` beats (from its message layout and the bus width), then stays idle
for its period minus its transfer, and must finish within its deadline (default: the period);
all are released at cycle 0, the worst case of simultaneous arrival. One run per candidate,
over `ProjectTraffic.cycles` (enough for `MESSAGES_RANKED` messages of the slowest
publisher), with the counter widths the hardware would get. Candidates are the six algorithms
and, with two or more publishers, the two-level combinations of the paper's most promising
pair (LRU over LOEDF and LST halves).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from rfc.dse.kernel import METRICS, run_replicates
from rfc.dse.objective import Candidate, Criterion, rank, reasons
from rfc.dse.sweep import ALGORITHMS
from rfc.errors import RfcError
from rfc.lib.schedulers.model import tree_of
from rfc.lib.schedulers.spec import AnySchedulerSpec, parse_scheduler

#: Shortest simulation of a project, in cycles.
MIN_CYCLES = 10_000
#: Messages the slowest publisher sends within the simulated horizon (at least `MIN_CYCLES`),
#: so that every task set is ranked on enough messages whatever its periods.
MESSAGES_RANKED = 10


class PublisherTiming(Protocol):
    """What the DSE reads of one scheduler input (`rfc.ir.infrastructure.SchedulerInput`).

    The DSE sits below the IR: it takes the scheduler's inputs as plain values, not the model.
    """

    @property
    def publisher(self) -> str:
        """The publisher block."""
        ...

    @property
    def transfer_beats(self) -> int:
        """Beats of one transfer, chunk header included."""
        ...

    @property
    def period(self) -> int | None:
        """Clock cycles between messages, when given."""
        ...

    @property
    def deadline(self) -> int | None:
        """Relative deadline in clock cycles, when given (implicit: the period)."""
        ...


@dataclass(frozen=True)
class ProjectTraffic:
    """The scheduler inputs of a project, in input order (= publisher id)."""

    publishers: tuple[str, ...]
    transfer: tuple[int, ...]
    period: tuple[int, ...]
    deadline: tuple[int, ...]
    horizon: int | None = None
    """Cycles to simulate, when the user chose them (``rfc dse --horizon``)."""

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
        """Simulated cycles: the horizon chosen, else `MESSAGES_RANKED` slowest periods."""
        if self.horizon is not None:
            return self.horizon
        return max(MIN_CYCLES, MESSAGES_RANKED * max(self.period))

    @property
    def messages(self) -> tuple[int, ...]:
        """Messages each publisher releases within the simulated cycles."""
        return tuple(-(-self.cycles // period) for period in self.period)


def project_traffic(
    project: str, inputs: Sequence[PublisherTiming], horizon: int | None = None
) -> ProjectTraffic:
    """The publishers' timing, simulated for `horizon` cycles if given.

    Args:
        project: The project's name, for messages.
        inputs: The scheduler's inputs in the holistic model, in input order.
        horizon: Cycles to simulate (default: `MESSAGES_RANKED` periods of the slowest).

    Raises:
        RfcError: A publisher has no period (the DSE cannot simulate it), or none exists.
    """
    if not inputs:
        raise RfcError(f"project '{project}' has no publisher in the logic to schedule")
    missing = [i.publisher for i in inputs if i.period is None]
    if missing:
        raise RfcError(
            f"publisher{'s' if len(missing) > 1 else ''} {', '.join(missing)} of project "
            f"'{project}' {'have' if len(missing) > 1 else 'has'} no period; "
            "rfc dse needs the period (and optionally the deadline) of every publisher",
            hint="add 'period: 100 us' (and 'deadline: ...') to each publisher block",
        )
    periods = [int(i.period) for i in inputs if i.period is not None]  # all, checked above
    for i, period in zip(inputs, periods, strict=True):
        if period < i.transfer_beats:
            raise RfcError(
                f"publisher {i.publisher} sends {i.transfer_beats} beats every {period} cycles: "
                "its own messages already overload the channel",
                hint="lengthen its period or widen the bus",
            )
    return ProjectTraffic(
        tuple(i.publisher for i in inputs),
        tuple(i.transfer_beats for i in inputs),
        tuple(periods),
        tuple(
            int(i.deadline) if i.deadline is not None else period
            for i, period in zip(inputs, periods, strict=True)
        ),
        horizon,
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


# Four tuples, like the wizard's SystemAnswers in shape only.
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
    traffic: ProjectTraffic,
    objective: Sequence[Criterion],
    names: Sequence[str] | None = None,
    *,
    progress: Callable[[int, int], None] | None = None,
) -> Recommendation:
    """Rank `names` (default `candidates`) for the project's publishers by `objective`.

    Args:
        traffic: The project's publishers (`project_traffic`).
        objective: The ranking criteria, most important first.
        names: The schedulers to rank.
        progress: Called with (candidates simulated, candidates) as the simulation goes.

    """
    chosen = list(names or candidates(traffic.n))
    evaluated = []
    for name in chosen:
        evaluated.append(evaluate(name, traffic))
        if progress is not None:
            progress(len(evaluated), len(chosen))
    ranking = rank(evaluated, objective, _resources(traffic))
    return Recommendation(
        traffic, tuple(objective), tuple(ranking), tuple(reasons(ranking, objective))
    )
