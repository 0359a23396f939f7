"""The DSE kernel's metrics: pinned on hand-made runs, and equal to the channel oracle.

`rfc.dse.channel.measure` derives the metrics from recorded signals alone; applied to a run of
the model API (`SchedulerModel.step`) driven by the NumPy `Publishers`, it must give exactly
what the compiled kernel (its own traffic, metrics folded per cycle) reports.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest

from rfc.dse.channel import measure
from rfc.dse.datasets import DATASETS, Traffic, draw
from rfc.dse.engine import build_tree, counter_bits, simulate, structure
from rfc.dse.kernel import COLUMN, METRICS, compiled
from rfc.dse.trace import record
from rfc.lib.schedulers.model.scheduler import SchedulerModel
from rfc.lib.schedulers.model.traffic import Publishers


def traffic(transfer, idle, deadline=None):
    t, f = np.array([transfer]), np.array([idle])
    return Traffic(t, f, t + f if deadline is None else np.array([deadline]))


def metrics(scheduler, run, cycles):
    return dict(zip(METRICS, simulate(scheduler, run, cycles)[0], strict=True))


def test_a_preemption_is_counted_once_and_the_definitions_hold():
    # PFP, T = (2, 6): input 1 holds the channel from cycle 3; input 0's second message arrives
    # at cycle 6 (last beat at 2, idle 3) and takes the channel at cycle 7, with 4 of input 1's
    # 6 beats moved; input 1 resumes at 9 and ends at 10.
    got = metrics("PFP", traffic([2, 6], [3, 50]), 11)
    assert got == pytest.approx(
        {
            "granted": 2,
            "completed": 2,
            "preemptions": (0 / 2 + 1 / 1) / 2,
            "response": (1 + 1 + 3) / 3,
            "lateness": ((2 - 5) + (8 - 11) + (10 - 56)) / 3,
            "max_lateness": -3,
            "utilization": 10 / 11,
            "messages": 3,
            "missed": 0,
        }
    )


def test_a_pending_message_past_its_deadline_counts_as_missed():
    got = metrics("NPFP", traffic([5, 5], [1, 1]), 8)
    assert got["messages"] == 1
    assert got["lateness"] == 5 - 6
    assert got["missed"] == 0.5  # input 1: due at cycle 6, still waiting at the end


def test_undefined_means_are_nan_without_a_completed_message():
    got = metrics("LOEDF", traffic([50, 50], [1, 1]), 20)
    assert got["messages"] == 0
    assert got["granted"] == 1
    assert math.isnan(got["response"])
    assert math.isnan(got["preemptions"])


@pytest.mark.parametrize(
    "scheduler", ["LRU", "NPFP", "PFP", "ROEDF", "LOEDF", "LST", "LRU(LOEDF,LST)"]
)
@pytest.mark.parametrize(("name", "n"), [("cc3", 5), ("large", 12)])
def test_the_kernel_equals_the_oracle_on_the_model_api(scheduler, name, n):
    replicates, cycles = 3, 2_500
    drawn = draw(DATASETS[name], n, replicates)
    rows = simulate(scheduler, drawn, cycles)
    for r in range(replicates):
        one = Traffic(drawn.transfer[r : r + 1], drawn.idle[r : r + 1], drawn.deadline[r : r + 1])
        tree = build_tree(structure(scheduler, n), one, counter_bits(drawn, cycles))
        run = record(SchedulerModel(tree), Publishers(one.transfer, gap=one.idle), cycles)
        expected = measure(run.request, run.last, run.grant, one.deadline[0])
        assert np.array_equal(rows[r], expected, equal_nan=True), (scheduler, r)
    assert rows[:, COLUMN["messages"]].min() > 0


def test_the_kernel_counts_as_compiled_only_when_numbas_cache_holds_it(tmp_path):
    probe = "from rfc.dse.kernel import compiled; print(compiled())"
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    empty = subprocess.run(
        [sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True
    )
    assert empty.stdout.split() == ["False"]
    simulate("LRU", draw(DATASETS["cc1"], 2, 1), 10)  # this process: the suite's own cache
    assert compiled()
