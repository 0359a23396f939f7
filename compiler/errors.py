"""Errors in the user's input, and the near-miss suggestions that come with them.

Every error a user can cause is an `RfcError`: the command line prints it as one message (with
the spec's file:line:col when known), exits with status 1 and shows no traceback. Anything else
escaping is a bug in rfc. The processor-side runtime reports its errors with the same class: this
module needs nothing but the standard library, so the node imports it without the compiler's
dependencies.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

__all__ = ["RfcError", "SourceLocation", "closest", "did_you_mean", "located"]


@dataclass(frozen=True)
class SourceLocation:
    """Where a spec element was written: file, 1-based line and column."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class RfcError(Exception):
    """An error in the user's input: a sentence, where it happened, and a way out.

    Args:
        message: What is wrong, naming the bad value and what was expected.
        location: The spec element responsible, when the input came from a spec.
        hint: A suggestion, such as the closest valid name.
    """

    def __init__(
        self, message: str, *, location: SourceLocation | None = None, hint: str | None = None
    ) -> None:
        super().__init__(message)
        self.message = message
        self.location = location
        self.hint = hint

    def __str__(self) -> str:
        where = f"{self.location}: " if self.location else ""
        text = f"{where}{self.message}"
        if self.hint:
            text += f"\n  hint: {self.hint}"
        return text


@contextmanager
def located(location: SourceLocation) -> Iterator[None]:
    """Give an `RfcError` raised inside, that has no location, `location`.

    The hardware library works on plain data and knows no spec: the compiler calls it inside
    this context with the spec element the call is for, so the user learns which one to fix.
    """
    try:
        yield
    except RfcError as exc:
        if exc.location is not None:
            raise
        raise RfcError(exc.message, location=location, hint=exc.hint) from None


def closest(word: str, candidates: Iterable[str], limit: int = 3) -> list[str]:
    """Return up to `limit` candidates that look like `word`, best first."""
    pool = list(dict.fromkeys(candidates))
    exact_case = [c for c in pool if c.lower() == word.lower()]
    found = exact_case + difflib.get_close_matches(word, pool, n=limit, cutoff=0.6)
    if not found:
        lowered = {c.lower(): c for c in pool}
        found = [lowered[c] for c in difflib.get_close_matches(word.lower(), lowered, limit, 0.5)]
    return list(dict.fromkeys(found))[:limit]


def did_you_mean(word: str, candidates: Iterable[str], limit: int = 3) -> str | None:
    """Return a 'did you mean ...?' hint, or None when nothing is close."""
    found = closest(word, candidates, limit)
    if not found:
        return None
    return "did you mean " + " or ".join(f"'{c}'" for c in found) + "?"
