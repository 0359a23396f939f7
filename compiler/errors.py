"""Errors in the user's input, and the near-miss suggestions that come with them.

Every error a user can cause is an `RfcError`: the command line prints it as one message (with
the spec's file:line:col when known), exits with status 1 and shows no traceback. Anything else
escaping is a bug in rfc.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

from rfc.runtime.errors import RfcError, SourceLocation

__all__ = ["RfcError", "SourceLocation", "closest", "did_you_mean"]


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
