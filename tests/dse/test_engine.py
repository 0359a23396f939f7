"""Running points: chunks on worker processes give the rows one process gives, in order."""

from __future__ import annotations

import numpy as np
import pytest

from rfc.dse import engine
from rfc.dse.datasets import DATASETS, draw
from rfc.dse.engine import TasksFailedError, chunks, counter_bits, run_tasks, simulate
from rfc.dse.sweep import COMBINATIONS, Plan, tasks_of
from rfc.lib.schedulers.spec import default_counter_bits
from tests.support.dask_cluster import dask_scheduler  # noqa: F401 (a fixture)


def test_counters_are_widened_beyond_the_run():
    drawn = draw(DATASETS["cc1"], 64, 2)
    bits = counter_bits(drawn, 50_000)
    assert 2 ** (bits - 1) > 50_000 + drawn.transfer.max() + drawn.deadline.max()
    default = default_counter_bits([int(drawn.transfer.max())], [int(drawn.deadline.max())])
    assert bits > default
    assert counter_bits(drawn, 10) == default


def test_chunks_on_two_processes_equal_one_process(monkeypatch):
    monkeypatch.setattr(engine, "CHUNK", 3)
    drawn = draw(DATASETS["cc4"], 6, 7)
    tasks = chunks(("cc4", "LST", 6), "LST", drawn, 1_500) + chunks(
        ("cc4", "LRU(LOEDF,LST)", 6), "LRU(LOEDF,LST)", drawn, 1_500
    )
    assert len(tasks) == 6
    shares = []
    parallel = run_tasks(tasks, jobs=2, advance=shares.append)
    assert sum(shares) == pytest.approx(1.0)
    assert np.array_equal(parallel["cc4", "LST", 6], simulate("LST", drawn, 1_500), equal_nan=True)
    serial = run_tasks(tasks, jobs=1)
    for key, rows in serial.items():
        assert np.array_equal(rows, parallel[key], equal_nan=True)


def test_the_first_replicates_do_not_depend_on_how_many_run():
    few = simulate("ROEDF", draw(DATASETS["large"], 8, 2), 3_000)
    many = simulate("ROEDF", draw(DATASETS["large"], 8, 5), 3_000)
    assert np.array_equal(few, many[:2], equal_nan=True)


def test_the_plan_adds_figure_14_at_the_largest_n_of_the_first_dataset():
    _, info = tasks_of(Plan(datasets=("cc1", "cc2"), sizes=(4, 8), replicates=2))
    combined = {key for key in info if key[1] in COMBINATIONS}
    assert combined == {("cc1", name, 8) for name in COMBINATIONS}
    assert len(info) == 2 * 2 * 6 + 3


def test_tasks_on_a_dask_cluster_equal_one_process(monkeypatch, dask_scheduler):  # noqa: F811
    monkeypatch.setattr(engine, "CHUNK", 2)
    drawn = draw(DATASETS["cc1"], 4, 5)
    tasks = chunks(("cc1", "LOEDF", 4), "LOEDF", drawn, 800) + chunks(
        ("cc1", "LRU(LOEDF,LST)", 4), "LRU(LOEDF,LST)", drawn, 800
    )
    shares = []
    clustered = run_tasks(tasks, jobs=1, advance=shares.append, cluster=dask_scheduler)
    assert sum(shares) == pytest.approx(1.0)
    serial = run_tasks(tasks, jobs=1)
    assert clustered.keys() == serial.keys()
    for key, rows in serial.items():
        assert np.array_equal(rows, clustered[key], equal_nan=True)


def test_a_failing_task_on_the_cluster_is_named_and_the_other_points_kept(dask_scheduler):  # noqa: F811
    drawn = draw(DATASETS["cc1"], 4, 2)
    tasks = chunks(("cc1", "LST", 4), "LST", drawn, 500) + chunks(
        ("cc1", "EDF", 4), "EDF", drawn, 500
    )
    with pytest.raises(TasksFailedError) as failed:
        run_tasks(tasks, jobs=1, cluster=dask_scheduler)
    assert len(failed.value.failures) == 1
    assert failed.value.failures[0].startswith("EDF N=4 cc1 replicates 0-1: RfcError")
    assert np.array_equal(failed.value.rows["cc1", "LST", 4], simulate("LST", drawn, 500))
    assert list(failed.value.rows) == [("cc1", "LST", 4)]
