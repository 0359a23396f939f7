"""A running two-worker Dask cluster for the tests of `--cluster ADDRESS`, shared per module."""

from __future__ import annotations

import pytest
from distributed import LocalCluster


@pytest.fixture(scope="module")
def dask_scheduler():
    """The address of a two-worker cluster (threads: quick to start; the jobs are independent)."""
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, protocol="tcp", dashboard_address=None
    ) as cluster:
        yield cluster.scheduler_address
