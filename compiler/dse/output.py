"""Writing DSE results into their directory at once (or not at all), and the project document.

A sweep writes ``results.json`` (the `--json` document), ``results.csv``, ``resources.csv``,
``table3.md``, ``report.html``, with `--figures` ``figure6…14`` and ``table3`` as PNG and SVG
(drawing them takes longer than a small sweep's simulation) and with `--verify-hdl`
``verify.json``. A project writes ``recommendation.json``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from rfc.dse.tables import document, resources_csv, results_csv, table3_markdown
from rfc.files.directory import replace_directory

if TYPE_CHECKING:  # the GHDL verification and the project's ranking load only when used
    from rfc.dse.objective import Candidate
    from rfc.dse.project import Recommendation
    from rfc.dse.sweep import SweepResult
    from rfc.dse.verify import Check


def write_sweep(
    result: SweepResult,
    checks: Sequence[Check],
    directory: Path,
    jobs: int = 1,
    figures: bool = False,
) -> None:
    """Replace `directory` with the sweep's tables and report, and its figures if asked.

    Args:
        result: The sweep.
        checks: The `--verify-hdl` checks (none: no ``verify.json``).
        directory: Replaced as a whole, or left as it was on an error.
        jobs: Processes drawing the figures.
        figures: Also draw the figures, which the report then shows.
    """
    from rfc.dse.report import render

    def fill(staging: Path) -> None:
        (staging / "results.json").write_text(json.dumps(document(result), indent=1) + "\n")
        (staging / "results.csv").write_text(results_csv(result))
        if result.resources:
            (staging / "resources.csv").write_text(resources_csv(result))
            (staging / "table3.md").write_text(table3_markdown(result))
        drawn: list[str] = []
        if figures:
            from rfc.dse.plots import write_figures  # matplotlib is imported only then

            drawn = write_figures(result, staging, jobs)
        (staging / "report.html").write_text(render(result, drawn), encoding="utf-8")
        if checks:
            verified = [check.as_dict() for check in checks]
            (staging / "verify.json").write_text(json.dumps(verified, indent=1) + "\n")

    replace_directory(directory, str(directory), fill, command="rfc dse")


def _candidate(candidate: Candidate) -> dict[str, object]:
    metrics = {k: None if math.isnan(v) else v for k, v in candidate.metrics.items()}
    return {"scheduler": candidate.scheduler, "metrics": metrics, **candidate.resources}


def recommendation_document(project: str, recommendation: Recommendation) -> dict[str, object]:
    """The `rfc dse SPEC --json` document."""
    traffic = recommendation.traffic
    return {
        "project": project,
        "recommended": recommendation.scheduler,
        "reasons": list(recommendation.reasons),
        "objective": [criterion.name for criterion in recommendation.objective],
        "cycles": traffic.cycles,
        "publishers": [
            {"name": name, "transfer_beats": t, "period": p, "deadline": d, "messages": m}
            for name, t, p, d, m in zip(
                traffic.publishers,
                traffic.transfer,
                traffic.period,
                traffic.deadline,
                traffic.messages,
                strict=True,
            )
        ],
        "ranking": [_candidate(candidate) for candidate in recommendation.ranking],
    }


def write_recommendation(report: dict[str, object], directory: Path) -> None:
    """Replace `directory` with ``recommendation.json``."""

    def fill(staging: Path) -> None:
        (staging / "recommendation.json").write_text(json.dumps(report, indent=1) + "\n")

    replace_directory(directory, str(directory), fill, command="rfc dse")
