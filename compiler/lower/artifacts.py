"""What a lowering produces: artifacts (generated files held in memory), and its options."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

from rfc.ir.model import Design


@dataclass(frozen=True)
class BuildOptions:
    """What the user asked ``rfc build`` for."""

    emit_ir: bool = False
    """Write the holistic model (``model.yaml``)."""


@dataclass(frozen=True)
class Artifact:
    """One generated file.

    Attributes:
        path: Where it goes, relative to the output directory (``/``-separated).
        kind: What it is, as the report's line-count table names it.
        text: Its contents.
    """

    path: str
    kind: str
    text: str

    @property
    def lines(self) -> int:
        """Non-blank lines: the paper's lines-of-code measure."""
        return count_lines(self.text)


Lowering = Callable[[Design, BuildOptions], Iterable[Artifact]]


def count_lines(text: str) -> int:
    """Non-blank lines, comments included: how the paper counts Listing 1 as 33 lines."""
    return sum(1 for line in text.splitlines() if line.strip())
