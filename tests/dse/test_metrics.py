"""Mean and 95 % confidence interval over replicates."""

from __future__ import annotations

import math

import pytest

from rfc.dse.metrics import summarize, t_quantile_95


@pytest.mark.parametrize(
    ("freedom", "quantile"),
    # Student's t, 97.5 % quantiles from the standard tables
    [(1, 12.706), (3, 3.182), (9, 2.262), (30, 2.042), (40, 2.021), (60, 2.000), (120, 1.980)],
)
def test_student_t_quantiles(freedom, quantile):
    assert t_quantile_95(freedom) == pytest.approx(quantile, abs=6e-4)


def test_interval_of_a_small_sample():
    summary = summarize([1.0, 2.0, 3.0, 4.0])
    assert summary.mean == 2.5
    assert summary.ci95 == pytest.approx(3.182 * math.sqrt(5 / 3) / 2, rel=1e-4)
    assert (summary.low, summary.high) == (summary.mean - summary.ci95, summary.mean + summary.ci95)


def test_undefined_replicates_are_left_out():
    summary = summarize([math.nan, 4.0, math.nan, 6.0])
    assert (summary.mean, summary.count) == (5.0, 2)
    assert summarize([7.0]).as_dict() == {
        "mean": 7.0, "ci95": 0.0, "low": 7.0, "high": 7.0, "replicates": 1,
    }  # fmt: skip
    assert summarize([math.nan]).as_dict()["mean"] is None
