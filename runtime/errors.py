"""Errors a user can cause, as the compiler and the runtime both report them.

An `RfcError` is printed as one message (with the spec's file:line:col when known) and ends the
command or the node with exit status 1 and no traceback. It lives in the runtime so that the
processor side, shipped without the compiler, reports its errors the same way.
"""

from __future__ import annotations

from dataclasses import dataclass


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
