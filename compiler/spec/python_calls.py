"""Call sites and argument checks shared by the Python front-end's functions."""

from __future__ import annotations

import inspect
import os
import sys
from collections.abc import Iterable, Mapping
from pathlib import Path
from types import FrameType
from typing import Any

from rfc.errors import RfcError, SourceLocation


def call_site() -> tuple[SourceLocation, Path]:
    """Where the user called into rfc: the first frame outside the rfc package."""
    frame: FrameType | None = sys._getframe(1)
    while frame is not None and frame.f_globals.get("__name__", "").split(".")[0] == "rfc":
        frame = frame.f_back
    if frame is None:  # called from rfc itself (tests of this module do not do that)
        return SourceLocation("<rfc>", 1, 1), Path.cwd()
    info = inspect.getframeinfo(frame, context=0)
    column = info.positions.col_offset if info.positions else None
    path = Path(info.filename)
    return SourceLocation(_display(path), info.lineno, (column or 0) + 1), path.resolve().parent


def _display(path: Path) -> str:
    """Name a file as the user sees it: relative to the working directory when inside it."""
    if path.is_absolute() and path.is_relative_to(Path.cwd()):
        return os.path.relpath(path)
    return str(path)


def as_text(value: Any, what: str, location: SourceLocation) -> str:
    """Return `value` if it is a string; raise at the user's call otherwise."""
    if not isinstance(value, str):
        raise RfcError(f"{what} must be a string, not {value!r}", location=location)
    return value


def as_texts(value: Any, what: str, location: SourceLocation) -> tuple[str, ...]:
    """Return a string or an iterable of strings as a tuple; raise otherwise."""
    items = (value,) if isinstance(value, str) else value
    if not isinstance(items, Iterable) or isinstance(items, Mapping):
        raise RfcError(
            f"{what} must be a string or a list of strings, not {value!r}", location=location
        )
    return tuple(as_text(item, f"each of {what}", location) for item in items)
