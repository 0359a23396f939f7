"""The progress of the commands that count through long work (replays, synthesis jobs)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TypeVar

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from rfc.cluster import Failure, run_jobs

J = TypeVar("J")
R = TypeVar("R")


def counting_bar(label: str, *, hidden: bool = False, percent: bool = False) -> Progress:
    """A bar on stderr counting done of total (or, with `percent`, its share), gone at the end.

    It shows only on a terminal, so piped output and logs stay clean; `hidden` also hides it
    (while a command prints JSON, say).
    """
    console = Console(stderr=True, highlight=False)
    return Progress(
        TextColumn(label),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%") if percent else MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=hidden or not console.is_terminal,
    )


def run_counted(
    label: str,
    function: Callable[[J], R],
    jobs: Sequence[J],
    describe: Callable[[J], str],
    *,
    workers: int,
    address: str | None,
    hidden: bool = False,
) -> tuple[list[R | None], list[Failure]]:
    """`rfc.cluster.run_jobs` with a `counting_bar` that advances as each job finishes."""
    with counting_bar(label, hidden=hidden) as bar:
        task = bar.add_task(label, total=len(jobs))
        return run_jobs(
            function,
            jobs,
            describe,
            workers=workers,
            address=address,
            finished=lambda *_: bar.advance(task),
        )
