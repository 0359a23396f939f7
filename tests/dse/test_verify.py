"""--verify-hdl: a difference in the metrics or in the hardware's grants fails the check.

That the generated hardware passes is proven by `rfc dse --verify-hdl` in tests/cli/test_dse.py.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from rfc.dse import verify
from rfc.dse.kernel import COLUMN
from rfc.dse.sweep import Plan, SweepResult, run_sweep
from rfc.lib.schedulers.model import model_of
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec


@pytest.fixture(scope="module")
def sweep():
    plan = Plan(datasets=("large",), sizes=(3,), replicates=2, combinations=False)
    return run_sweep(plan, jobs=1, synthesis=False)


def test_a_metric_that_differs_fails_the_check(sweep, tmp_path):
    point = sweep.point("large", "ROEDF", 3)
    rows = point.rows.copy()
    rows[0, COLUMN["lateness"]] += 0.5
    tampered = SweepResult(
        sweep.plan,
        tuple(replace(p, rows=rows) if p is point else p for p in sweep.points),
        sweep.resources,
    )
    check = verify._check(tampered, "ROEDF", "large", 3, tmp_path)
    assert check.error is None
    assert not check.equal
    assert check.as_dict()["dse"]["lateness"] == check.as_dict()["ghdl"]["lateness"] + 0.5
    others = {name: value for name, value in check.as_dict()["dse"].items() if name != "lateness"}
    assert others.items() <= check.as_dict()["ghdl"].items()


def test_hardware_that_grants_otherwise_fails_the_check(sweep, tmp_path, monkeypatch):
    # the trace comes from a fixed-priority model while the hardware generated is LRU
    def other_model(spec: SchedulerSpec):
        return model_of(replace(spec, algorithm=Algorithm.NPFP))

    monkeypatch.setattr(verify, "model_of", other_model)
    check = verify._check(sweep, "LRU", "large", 3, tmp_path)
    assert not check.equal
    assert check.measured is None
    assert "model grants" in check.error
    assert "GHDL" in check.error
