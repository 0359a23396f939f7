"""Jobs on Dask: the serial run's results, in job order, a failing job named, the others kept."""

from __future__ import annotations

import math

import pytest

from rfc.cluster import Failure, run_jobs
from rfc.errors import RfcError
from tests.support.dask_cluster import dask_scheduler  # noqa: F401 (a fixture)

JOBS = [4.0, -1.0, 9.0, 2.25]


def describe(x: float) -> str:
    return f"x={x}"


def test_serial_keeps_the_others_and_names_the_failing_job():
    done = []
    results, failures = run_jobs(math.sqrt, JOBS, describe, finished=lambda j, r: done.append(j))
    assert results == [2.0, None, 3.0, 1.5]
    assert failures == [Failure("x=-1.0", "ValueError: math domain error")]
    assert done == JOBS


def test_a_local_cluster_of_two_processes_gives_the_serial_results():
    done = []
    results, failures = run_jobs(
        math.sqrt, JOBS, describe, workers=2, finished=lambda j, r: done.append(j)
    )
    assert (results, failures) == run_jobs(math.sqrt, JOBS, describe)
    assert sorted(done) == sorted(JOBS)


def test_an_existing_scheduler_gives_the_serial_results(dask_scheduler):  # noqa: F811
    assert run_jobs(math.sqrt, JOBS, describe, address=dask_scheduler) == run_jobs(
        math.sqrt, JOBS, describe
    )


def test_no_scheduler_at_the_address_is_one_clear_error():
    with pytest.raises(RfcError, match=r"127\.0\.0\.1:9: no Dask scheduler answers"):
        run_jobs(math.sqrt, JOBS, describe, address="tcp://127.0.0.1:9")
