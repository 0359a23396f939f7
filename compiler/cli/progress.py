"""The progress bar of the commands that count through long work (replays, synthesis jobs)."""

from __future__ import annotations

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn


def counting_bar(label: str, *, hidden: bool = False) -> Progress:
    """A bar on stderr counting done of total, gone when the work ends.

    It shows only on a terminal, so piped output and logs stay clean; `hidden` also hides it
    (while a command prints JSON, say).
    """
    console = Console(stderr=True, highlight=False)
    return Progress(
        TextColumn(label),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=hidden or not console.is_terminal,
    )
