"""Every lowering, and `lower`, which runs them and then the report (see `rfc.lower`)."""

from __future__ import annotations

from rfc.ir.model import Design
from rfc.lower.artifacts import Artifact, BuildOptions, Lowering, ReportSection
from rfc.lower.hardware import hardware
from rfc.lower.hls_headers import hls_headers
from rfc.lower.model import holistic_model
from rfc.lower.node import processor_node
from rfc.lower.report import build_report

#: Every lowering, in the order their artifacts are listed in the report.
LOWERINGS: tuple[Lowering, ...] = (holistic_model, hardware, hls_headers, processor_node)


def lower(design: Design, options: BuildOptions, spec_text: str) -> tuple[Artifact, ...]:
    """Produce every artifact of the design, then the report about them.

    Args:
        design: The holistic model (stage DERIVED).
        options: What to build.
        spec_text: The spec's text, for the report's line count.
    """
    produced = [item for lowering in LOWERINGS for item in lowering(design, options)]
    artifacts = tuple(a for a in produced if isinstance(a, Artifact))
    sections = tuple(s for s in produced if isinstance(s, ReportSection))
    return (*artifacts, build_report(design, spec_text, artifacts, sections))
