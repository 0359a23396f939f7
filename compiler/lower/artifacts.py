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
    estimate: bool = False
    """Estimate the logic's LUT/FF with Yosys for the report."""
    hardware: bool = True
    """Generate the logic and its vendor scripts (off: model, software and report only)."""


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


@dataclass(frozen=True)
class ReportSection:
    """A section a lowering adds to report.md (measured figures, not a file of its own).

    Attributes:
        title: The section's heading.
        lines: Its Markdown lines.
    """

    title: str
    lines: tuple[str, ...]


Lowering = Callable[[Design, BuildOptions], Iterable[Artifact | ReportSection]]


def count_lines(text: str) -> int:
    """Non-blank lines, comments included: how the paper counts Listing 1 as 33 lines."""
    return sum(1 for line in text.splitlines() if line.strip())
