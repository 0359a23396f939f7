"""The holistic model artifact: the IR text after every pass (``--emit-ir``)."""

from __future__ import annotations

from collections.abc import Iterable

from rfc.ir.model import Design
from rfc.ir.text import format_ir
from rfc.lower.artifacts import Artifact, BuildOptions

#: The file name of the holistic model.
MODEL_FILE = "model.yaml"


def holistic_model(design: Design, options: BuildOptions) -> Iterable[Artifact]:
    """The paper's template configuration: every field, id and derived part explicit."""
    if options.emit_ir:
        yield Artifact(MODEL_FILE, "holistic model", format_ir(design))
