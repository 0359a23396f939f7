"""Independent jobs on Dask distributed: a local cluster of worker processes, or an existing one.

The sweeps (`rfc dse --cluster`, `rfc sched synth --n LIST`) and batch simulations (`rfc sim`
over many bags) hand their jobs to `run_jobs`: in this process when one worker is asked for,
else on a new local cluster of `workers` processes, or on the scheduler at `address`. Results
come back in the jobs' order whatever the order they finish in, so they equal the serial run's.
A job that raises does not stop the others: it is returned as a `Failure` naming the job.
Dask is an optional extra (``pip install 'rfc[cluster]'``), imported only here and only when used.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from dataclasses import dataclass
from typing import Any, TypeVar

from rfc.errors import RfcError

J = TypeVar("J")
R = TypeVar("R")


# Two names and a __str__, like rfc.lower.system.top.Terminal in shape only: a job, not a port.
@dataclass(frozen=True)
class Failure:
    """A job that raised: which one (its parameters, as the user gave them) and the error."""

    job: str
    error: str

    def __str__(self) -> str:
        return f"{self.job}: {self.error}"


def run_jobs(
    function: Callable[[J], R],
    jobs: Sequence[J],
    describe: Callable[[J], str],
    *,
    workers: int = 1,
    address: str | None = None,
    finished: Callable[[J, R | None], None] | None = None,
) -> tuple[list[R | None], list[Failure]]:
    """Run `function` on every job; return the results in job order and the failures.

    Args:
        function: A top-level function (it is sent to the workers), one job in, its result out.
        jobs: The jobs.
        describe: A job's parameters in words, for a failure's message.
        workers: Worker processes of a local cluster; 1 (and no `address`): in this process.
        address: A running Dask scheduler (``tcp://host:8786``) instead of a local cluster.
        finished: Called as each job ends (None for a failed one), for a progress bar.

    Returns:
        Each job's result (None where it failed), and one `Failure` per failed job.

    Raises:
        RfcError: Dask is not installed, or no scheduler answers at `address`.
    """
    results: list[R | None] = [None] * len(jobs)
    failures: dict[int, Failure] = {}

    def record(index: int, result: R | None, error: BaseException | None) -> None:
        if error is not None:
            failures[index] = Failure(describe(jobs[index]), _message(error))
        results[index] = result
        if finished is not None:
            finished(jobs[index], result)

    if workers <= 1 and address is None:
        for index, job in enumerate(jobs):
            try:
                result = function(job)
            except Exception as error:  # a failing job is reported, the others run
                record(index, None, error)
            else:
                record(index, result, None)
    else:
        _on_dask(function, jobs, workers, address, record)
    return results, [failures[index] for index in sorted(failures)]


def _on_dask(
    function: Callable[[Any], Any],
    jobs: Sequence[Any],
    workers: int,
    address: str | None,
    record: Callable[[int, Any, BaseException | None], None],
) -> None:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise RfcError(
            "running jobs on a Dask cluster needs Dask, which is not installed",
            hint="pip install 'rfc[cluster]', or leave out --jobs/--cluster to run them here",
        ) from None
    with ExitStack() as stack:
        if address is None:
            cluster = LocalCluster(
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
                silence_logs=logging.CRITICAL,  # a closing worker logs its lost scheduler
            )
            stack.enter_context(cluster)
            client = stack.enter_context(Client(cluster))
        else:
            client = stack.enter_context(_connect(Client, address))
        futures = client.map(function, list(jobs), pure=False)
        index = {future.key: n for n, future in enumerate(futures)}
        for future in as_completed(futures):
            error = future.exception()
            record(index[future.key], None if error else future.result(), error)


def _connect(client: type, address: str) -> Any:
    try:
        return client(address, timeout="5s")
    except (OSError, TimeoutError, ValueError) as error:  # ValueError: not an address
        raise RfcError(
            f"--cluster {address}: no Dask scheduler answers there ({error})",
            hint="start one with `dask scheduler` and its workers with `dask worker ADDRESS`, "
            "or use --jobs N for a local cluster",
        ) from None


def _message(error: BaseException) -> str:
    text = str(error).strip().splitlines()
    return f"{type(error).__name__}: {text[0]}" if text else type(error).__name__
