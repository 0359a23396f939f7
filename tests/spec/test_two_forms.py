"""One system, two forms: the YAML spec and the Python spec lower to identical IR text."""

from __future__ import annotations

from pathlib import Path

import pytest

from rfc.ir.text import format_ir
from rfc.passes.pipeline import MODEL_PIPELINE, run_pipeline
from rfc.spec import load_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
PAIRS = {
    "listing 1 (HLS, ROS 1)": ROOT / "examples" / "rotation_converter" / "RotationConverterNode",
    "image pipeline (include/exclude)": ROOT / "examples" / "image_pipeline" / "ImagePipeline",
    "image pipeline, HLS stages": ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls",
    "MyHDL accelerator (ROS 2, timing)": Path(__file__).parent / "systems" / "quat_myhdl",
}


def texts_after_each_pass(path):
    """The IR after each pass deriving the model (the image pipeline's logic is refused)."""
    seen = []
    design = load_spec(path)
    run_pipeline(design, MODEL_PIPELINE, lambda name, d: seen.append((name, format_ir(d))))
    return seen


@pytest.mark.parametrize("stem", PAIRS.values(), ids=PAIRS.keys())
def test_yaml_and_python_forms_give_the_same_ir_after_every_pass(stem):
    from_yaml = texts_after_each_pass(stem.with_suffix(".yaml"))
    from_python = texts_after_each_pass(stem.with_suffix(".py"))
    assert [name for name, _ in from_yaml][-1] == "derive-infrastructure"
    for (name, yaml_text), (_, python_text) in zip(from_yaml, from_python, strict=True):
        assert python_text == yaml_text, f"the forms differ after {name}"


def test_both_forms_emit_the_same_holistic_model_through_the_cli(tmp_path):
    stem = PAIRS["image pipeline (include/exclude)"]
    models = []
    for suffix in (".yaml", ".py"):
        out = tmp_path / suffix.strip(".")
        result = run_rfc("build", stem.with_suffix(suffix), "-o", out, "--emit-ir", "--no-hardware")
        assert result.returncode == 0, result.stderr
        models.append((out / "model.yaml").read_text())
    assert models[0] == models[1]
