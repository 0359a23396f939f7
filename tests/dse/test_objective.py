"""Lexicographic ranking: order, lazy synthesis, reasons, and objective errors."""

from __future__ import annotations

import math

import pytest

from rfc.dse.objective import Candidate, parse_objective, rank, reasons
from rfc.errors import RfcError


def candidate(name, completed, missed, lateness):
    return Candidate(name, {"completed": completed, "missed": missed, "max_lateness": lateness})


def luts(table, asked):
    def synthesize(candidate):
        asked.append(candidate.scheduler)
        return {"lut": table[candidate.scheduler], "ff": 1}

    return synthesize


def test_criteria_apply_in_order_and_luts_only_where_they_decide():
    pool = [
        candidate("A", 4, 0.0, -3),
        candidate("B", 5, 0.2, -9),
        candidate("C", 5, 0.0, -9),
        candidate("D", 5, 0.0, -9),
        candidate("E", 5, 0.0, -1),
    ]
    asked = []
    ranking = rank(
        pool, parse_objective("completed,missed,max_lateness,lut"), luts({"C": 90, "D": 40}, asked)
    )
    assert [c.scheduler for c in ranking] == ["D", "C", "E", "B", "A"]
    assert sorted(asked) == ["C", "D"]


def test_higher_is_better_for_completed_and_nan_ranks_last():
    pool = [candidate("A", 2, math.nan, 0), candidate("B", 2, 0.5, 0)]
    ranking = rank(pool, parse_objective("completed,missed"), luts({}, []))
    assert [c.scheduler for c in ranking] == ["B", "A"]


def test_reasons_name_the_deciding_criterion_and_the_runner_up():
    objective = parse_objective("completed,missed,max_lateness")
    ranking = rank(
        [candidate("LST", 6, 0.0, -5), candidate("LOEDF", 6, 0.0, -9)], objective, luts({}, [])
    )
    said = reasons(ranking, objective)
    assert said[0] == "accelerators that completed a message: 6, as good as LST"
    assert said[1] == "messages that missed their deadline: 0 %, as good as LST"
    assert said[2] == (
        "worst lateness: -9 cycles, better than the runner-up LST (-5 cycles): this decides"
    )


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("completed,latenes", "unknown objective criterion 'latenes'"),
        ("lut,lut", "names a criterion twice"),
        (" , ", "names no criterion"),
    ],
)
def test_bad_objectives_are_user_errors(text, message):
    with pytest.raises(RfcError, match=message):
        parse_objective(text)
