"""report.md and the lowering registry, in process."""

from __future__ import annotations

from pathlib import Path

from rfc.driver import compile_spec
from rfc.ir.text import format_ir
from rfc.lower import LOWERINGS, lower
from rfc.lower.artifacts import BuildOptions, count_lines
from tests.passes.specs import compile_yaml, pass_through

ROOT = Path(__file__).resolve().parents[2]
LISTING_1 = ROOT / "examples" / "rotation_converter" / "RotationConverterNode.yaml"


def test_lowering_produces_the_model_only_when_asked():
    design = compile_spec(LISTING_1)
    spec = LISTING_1.read_text()
    software_only = BuildOptions(hardware=False)
    node = ["sw/rotation_converter_node_node.py", "sw/rotation_converter_node_plan.json"]
    paths = [a.path for a in lower(design, software_only, spec)]
    assert paths == [*node, "sw/README.md", "report.md"]
    model, *_, report = lower(design, BuildOptions(emit_ir=True, hardware=False), spec)
    assert (model.path, model.kind, model.text) == (
        "model.yaml",
        "holistic model",
        format_ir(design),
    )
    assert f"| holistic model | 1 | {count_lines(model.text)} |" in report.text
    assert len(LOWERINGS) >= 1


def test_report_lists_buffers_when_a_publisher_needs_them(tmp_path):
    design = compile_yaml(tmp_path, pass_through("tf2_msgs/TFMessage"))
    report = lower(design, BuildOptions(hardware=False), "project: {}\n")[-1]
    assert "## Buffers" in report.text
    assert "| `Pub` | transforms |" in report.text
    assert "| publisher | 0 | `Pub` | `/Pub` | tf2_msgs/msg/TFMessage |" in report.text


def test_text_with_locations_says_where_each_node_was_written():
    design = compile_spec(LISTING_1)
    text = format_ir(design, locations=True)
    assert f'at: "{LISTING_1}:18:5"' in text  # the Quaternion_sub block
    assert "at:" not in format_ir(design)
