"""Questions at a terminal (with Tab completion), or answered from a file for scripting.

An answers file holds one answer per line, in the order the questions come; an empty line takes
the default, and questions past the end of the file take theirs. At a terminal a wrong answer
is explained and asked again; from a file it ends the session with that error.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import TypeVar

from rich.console import Console

from rfc.errors import RfcError, SourceLocation

T = TypeVar("T")
#: Turns an answer into a value, or raises RfcError located at the answer.
Check = Callable[[str, SourceLocation], T]


class Prompter:
    """Asks questions and returns checked answers.

    Args:
        answers: Replayed answers (one per question), or None to ask at the terminal.
        console: Where questions, trees and notes are shown.
    """

    def __init__(self, answers: Iterator[str] | None, console: Console, source: str) -> None:
        self._answers = answers
        self._source = source
        self._count = 0
        self.console = console

    @classmethod
    def from_file(cls, path: Path, console: Console) -> Prompter:
        """Replay the answers in `path`, one per line."""
        try:
            lines = path.read_text(encoding="utf-8").splitlines()
        except OSError as exc:
            raise RfcError(
                f"cannot read the answers file '{path}': {exc.strerror}",
                hint="give a text file with one answer per line",
            ) from None
        return cls(iter(lines), console, str(path))

    @classmethod
    def at_terminal(cls, console: Console) -> Prompter:
        """Ask at the terminal."""
        return cls(None, console, "answer")

    def note(self, text: str) -> None:
        """Show a line of explanation (not a question)."""
        self.console.print(text, highlight=False, markup=False)

    def ask(
        self,
        question: str,
        default: str,
        check: Check[T],
        *,
        complete: Sequence[str] = (),
    ) -> T:
        """Ask until the answer passes `check`; Enter takes `default`.

        Args:
            question: The question, without the default.
            default: The answer Enter gives (shown in brackets).
            check: Turns the answer (and where it was given: the answers file's line) into a
                value; raises RfcError when it is not acceptable.
            complete: Words offered by Tab at the terminal.
        """
        shown = f"{question} [{default}]: " if default else f"{question}: "
        while True:
            text = self._next(shown, complete).strip() or default
            self._count += 1
            try:
                return check(text, SourceLocation(self._source, self._count, 1))
            except RfcError as exc:
                if self._answers is not None:
                    raise
                hint = f" ({exc.hint})" if exc.hint else ""
                self.console.print(
                    f"  {exc.message}{hint}", highlight=False, markup=False, style="red"
                )

    def ask_yes(self, question: str, default: bool) -> bool:
        """Ask a yes/no question."""
        return self.ask(f"{question} (y/n)", "y" if default else "n", _yes_no)

    def _next(self, shown: str, complete: Sequence[str]) -> str:
        if self._answers is not None:
            answer = next(self._answers, "")
            self.console.print(f"{shown}{answer}", highlight=False, markup=False)
            return answer
        _set_completion(complete)
        self.console.file.flush()
        try:
            return input(shown)
        except EOFError:  # input closed: defaults from here on, and no asking again
            sys.stdout.write("\n")
            self._answers = iter(())
            return ""


def _yes_no(text: str, location: SourceLocation) -> bool:
    lowered = text.lower()
    if lowered in ("y", "yes"):
        return True
    if lowered in ("n", "no"):
        return False
    raise RfcError(
        f"'{text}' is not an answer to a yes/no question; expected y or n", location=location
    )


def _set_completion(words: Sequence[str]) -> None:
    """Offer `words` to Tab (readline is absent on some platforms: then there is none)."""
    try:
        import readline
    except ImportError:
        return
    candidates = sorted(words)

    def completer(text: str, state: int) -> str | None:
        found = [w for w in candidates if w.startswith(text)]
        return found[state] if state < len(found) else None

    readline.set_completer(completer)
    readline.set_completer_delims(" \t,")
    readline.parse_and_bind("tab: complete")
