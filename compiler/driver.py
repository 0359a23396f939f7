"""From a spec file to the holistic model: front-end, then the pass pipeline."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from rfc.ir.model import Design
from rfc.passes.base import Pass
from rfc.passes.pipeline import PIPELINE, run_pipeline
from rfc.spec import load_spec


def compile_spec(
    path: Path | str,
    *,
    after: Callable[[str, Design], None] | None = None,
    pipeline: tuple[Pass, ...] = PIPELINE,
) -> Design:
    """Read a YAML or Python spec and run the whole pipeline on it.

    Args:
        path: The spec; locations in errors name it as given here.
        after: Called with each stage's name (``parse``, then each pass) and its design.
        pipeline: The passes (`rfc build` adds resolve-scheduler: `BUILD_PIPELINE`).

    Returns:
        The holistic model (stage DERIVED).

    Raises:
        RfcError: The spec is wrong; the message names file:line:col.
    """
    return run_pipeline(load_spec(Path(path), str(path)), pipeline, after)
