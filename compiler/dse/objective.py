"""Ranking schedulers by a lexicographic objective, and saying why the first one wins.

An objective is an ordered list of criteria (``completed,missed,max_lateness,lut``): the
candidates are sorted by the first, ties broken by the next, and so on. Resource criteria
(LUT, FF) need a synthesis each, so they are looked up only for the candidates still tied
with the best one: the rest keep their order.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from rfc.errors import RfcError, did_you_mean


@dataclass(frozen=True)
class Criterion:
    """One thing to optimize: a metric (or resource) and its direction."""

    name: str
    label: str
    higher_is_better: bool
    unit: str = ""

    @property
    def resource(self) -> bool:
        """Whether it comes from synthesis rather than simulation."""
        return self.name in ("lut", "ff")

    def describe(self, value: float) -> str:
        """The value with its unit, for reasons."""
        if math.isnan(value):
            return "undefined"
        if self.name == "missed":
            return f"{100 * value:.3g} %"
        text = f"{value:.0f}" if float(value).is_integer() else f"{value:.4g}"
        return f"{text} {self.unit}".rstrip()


CRITERIA = {
    c.name: c
    for c in (
        Criterion("completed", "accelerators that completed a message", True),
        Criterion("missed", "messages that missed their deadline", False),
        Criterion("lateness", "mean lateness", False, "cycles"),
        Criterion("max_lateness", "worst lateness", False, "cycles"),
        Criterion("response", "mean response time", False, "cycles"),
        Criterion("preemptions", "preemptions per transaction", False),
        Criterion("utilization", "channel utilization", True),
        Criterion("lut", "LUTs", False),
        Criterion("ff", "flip-flops", False),
    )
}
#: Every accelerator completes → fewest missed deadlines → lowest worst lateness → fewest LUTs.
DEFAULT_OBJECTIVE = ("completed", "missed", "max_lateness", "lut")


def parse_objective(text: str) -> tuple[Criterion, ...]:
    """Criteria from a comma-separated list such as ``completed,missed,lut``.

    Raises:
        RfcError: An unknown or repeated criterion.
    """
    names = [part.strip().lower() for part in text.split(",") if part.strip()]
    if not names:
        raise RfcError(
            "the objective names no criterion", hint=f"for example {','.join(DEFAULT_OBJECTIVE)}"
        )
    for name in names:
        if name not in CRITERIA:
            raise RfcError(
                f"unknown objective criterion '{name}'; expected some of {', '.join(CRITERIA)}",
                hint=did_you_mean(name, list(CRITERIA)),
            )
    if len(set(names)) != len(names):
        raise RfcError(f"the objective '{text}' names a criterion twice")
    return tuple(CRITERIA[name] for name in names)


@dataclass
class Candidate:
    """A scheduler under evaluation: its metrics, and its resources once synthesized."""

    scheduler: str
    metrics: dict[str, float]
    resources: dict[str, int] = field(default_factory=dict)

    def value(self, criterion: Criterion) -> float:
        """The candidate's value for `criterion` (NaN when unknown)."""
        if criterion.resource:
            return float(self.resources.get(criterion.name, math.nan))
        return float(self.metrics[criterion.name])


def _sort_key(criterion: Criterion) -> Callable[[Candidate], tuple[bool, float]]:
    def key(candidate: Candidate) -> tuple[bool, float]:
        value = candidate.value(criterion)
        if math.isnan(value):
            return (True, 0.0)
        return (False, -value if criterion.higher_is_better else value)

    return key


def _split(group: list[Candidate], criterion: Criterion) -> list[list[Candidate]]:
    key = _sort_key(criterion)
    ordered = sorted(group, key=key)
    parts: list[list[Candidate]] = []
    for candidate in ordered:
        if parts and key(parts[-1][0]) == key(candidate):
            parts[-1].append(candidate)
        else:
            parts.append([candidate])
    return parts


def rank(
    candidates: Sequence[Candidate],
    objective: Sequence[Criterion],
    synthesize: Callable[[Candidate], dict[str, int]],
) -> list[Candidate]:
    """The candidates, best first, by `objective` (stable: the given order breaks full ties).

    Args:
        candidates: Evaluated schedulers.
        objective: Criteria in priority order.
        synthesize: Fills in a candidate's ``lut`` and ``ff`` (asked only where they decide).
    """
    groups = [list(candidates)]
    for criterion in objective:
        refined = []
        for index, group in enumerate(groups):
            if criterion.resource and index > 0:
                refined.append(group)
                continue
            if criterion.resource and len(group) > 1:
                for candidate in group:
                    if not candidate.resources:
                        candidate.resources = synthesize(candidate)
            refined += _split(group, criterion) if len(group) > 1 else [group]
        groups = refined
    return [candidate for group in groups for candidate in group]


def reasons(ranking: Sequence[Candidate], objective: Sequence[Criterion]) -> list[str]:
    """Why the first candidate wins: its value on each criterion up to the one that decides."""
    best = ranking[0]
    if len(ranking) == 1:
        return [f"the only candidate: {best.scheduler}"]
    runner = ranking[1]
    lines = []
    for criterion in objective:
        mine, theirs = best.value(criterion), runner.value(criterion)
        text = f"{criterion.label}: {criterion.describe(mine)}"
        tied = [c.scheduler for c in ranking[1:] if _same(c.value(criterion), mine)]
        if not _same(mine, theirs):
            lines.append(
                f"{text}, better than the runner-up {runner.scheduler} "
                f"({criterion.describe(theirs)}): this decides"
            )
            return lines
        lines.append(f"{text}, as good as {_names(tied)}")
    lines.append(f"ties on every criterion with {runner.scheduler}; listed first")
    return lines


def _same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b


def _names(names: Sequence[str]) -> str:
    if len(names) <= 3:
        return ", ".join(names)
    return f"{', '.join(names[:3])} and {len(names) - 3} more"
