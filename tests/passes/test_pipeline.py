"""The pipeline: its visible order, its passes' shape, and golden IR text after every pass.

Regenerate the golden files (after checking the change is intended) with
``RFC_UPDATE_GOLDEN=1 .venv/bin/pytest tests/passes/test_pipeline.py``.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import pytest

from rfc.errors import RfcError
from rfc.ir.model import Stage
from rfc.ir.text import format_ir
from rfc.passes.pipeline import PIPELINE, describe, pass_names, run_pipeline
from rfc.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = Path(__file__).parent / "golden"
SYSTEMS = {
    "rotation_converter": ROOT / "examples" / "rotation_converter" / "RotationConverterNode.yaml",
    "image_pipeline": ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml",
}
#: Systems the logic cannot hold yet, with the pass that says so and what it says.
REFUSED = {"image_pipeline": ("check-hardware", "the logic's buffers need")}
#: Passes that only warn: they return the design they are given, at its stage.
WARN_ONLY = ("check-timing",)


def test_the_pipeline_is_the_one_of_the_design():
    assert describe() == (
        "resolve-types → check-connections → expand-selections → flatten-messages → "
        "derive-infrastructure → check-hardware → check-timing"
    )
    assert pass_names()[0] == "parse"


@pytest.mark.parametrize("step", PIPELINE, ids=lambda p: p.name)
def test_each_pass_is_a_small_frozen_dataclass(step):
    assert dataclasses.is_dataclass(step)
    with pytest.raises(dataclasses.FrozenInstanceError):
        step.name = "other"  # type: ignore[misc]


def stages(system):
    """The designs after each pass; a refused system's stop before the pass that refuses it."""
    path, seen = SYSTEMS[system], []
    refused, message = REFUSED.get(system, (None, ""))
    pipeline = tuple(p for p in PIPELINE if p.name != refused and p.name not in WARN_ONLY)
    run_pipeline(load_spec(path, path.name), pipeline, lambda name, d: seen.append((name, d)))
    if refused:
        step = next(p for p in PIPELINE if p.name == refused)
        with pytest.raises(RfcError, match=message):
            step.apply(seen[-1][1])
    return seen


@pytest.mark.parametrize("system", SYSTEMS)
def test_each_pass_moves_one_stage_on_and_leaves_its_input_alone(system):
    seen = stages(system)
    assert [d.stage for _, d in seen] == list(Stage)[: len(seen)]
    texts = [format_ir(d) for _, d in seen]
    again = [format_ir(d) for _, d in seen]  # designs are frozen: rendering twice agrees
    assert texts == again
    assert len(set(texts)) == len(texts)


@pytest.mark.parametrize("system", SYSTEMS)
def test_ir_text_after_each_pass_matches_golden(system):
    for name, design in stages(system):
        golden = GOLDEN / f"{system}.{name}.yaml"
        text = format_ir(design)
        if os.environ.get("RFC_UPDATE_GOLDEN"):
            golden.write_text(text)
        assert text == golden.read_text(), f"IR after {name} differs from {golden.name}"


@pytest.mark.parametrize("name", WARN_ONLY)
def test_a_pass_that_only_warns_returns_the_design_it_is_given(name):
    step = next(p for p in PIPELINE if p.name == name)
    design = stages("rotation_converter")[-1][1]
    assert step.apply(design) is design
