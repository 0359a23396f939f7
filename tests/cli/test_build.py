"""`rfc check` and `rfc build`: the command-line contract (docs/architecture.md) for specs."""

from __future__ import annotations

from pathlib import Path

import pytest
from ruamel.yaml import YAML

from rfc.passes.pipeline import pass_names
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
LISTING_1 = ROOT / "examples" / "rotation_converter" / "RotationConverterNode.yaml"


def test_check_accepts_listing_1_as_printed():
    result = run_rfc("check", LISTING_1.name, cwd=LISTING_1.parent)
    assert result.returncode == 0, result.stderr
    assert result.stdout == (
        "ok: RotationConverterNode.yaml: project RotationConverterNode, 1 subscriber, "
        "1 publisher, 1 accelerator, 2 connections\n"
    )


@pytest.fixture(scope="module")
def listing_1_build(tmp_path_factory):
    out = tmp_path_factory.mktemp("listing1") / "build"
    result = run_rfc("build", LISTING_1, "-o", out, "--emit-ir")
    assert result.returncode == 0, result.stderr
    return out


def test_emit_ir_lists_every_field_of_quaternion_and_point(listing_1_build):
    model = YAML(typ="safe", pure=True).load((listing_1_build / "model.yaml").read_text())
    assert model["stage"] == "checked"  # the logic's rules hold too
    into, out_of = model["connections"]
    assert (into["message"], into["fields"]) == ("geometry_msgs/msg/Quaternion", list("xyzw"))
    assert (out_of["message"], out_of["fields"]) == ("geometry_msgs/msg/Point", list("xyz"))
    ports = {(b["name"], p["name"]): p for b in model["blocks"] for p in b["ports"]}
    rows = ports[("QuatToEuler_acc", "in0")]["fields"]
    assert [(r["path"], r["type"], r["offset"]) for r in rows] == [
        ("x", "float64", 0),
        ("y", "float64", 8),
        ("z", "float64", 16),
        ("w", "float64", 24),
    ]
    assert [r["path"] for r in ports[("Euler_pub", "in0")]["fields"]] == list("xyz")
    (subscriber,) = model["infrastructure"]["subscribers"]
    assert (subscriber["id"], subscriber["frame_bytes"]) == (0, 32)


def test_report_compares_spec_lines_with_generated_lines(listing_1_build):
    report = (listing_1_build / "report.md").read_text()
    assert "| system specification (written) | 1 | 33 | 1.0 |" in report
    model_lines = sum(
        1 for line in (listing_1_build / "model.yaml").read_text().splitlines() if line.strip()
    )
    assert f"| holistic model | 1 | {model_lines} |" in report
    assert "| subscriber | 0 | `Quaternion_sub` |" in report


@pytest.mark.parametrize("name", pass_names())
def test_dump_ir_after_each_pass(tmp_path, name):
    result = run_rfc("build", LISTING_1, "-o", tmp_path / "out", "--dump-ir-after", name)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith(f"# IR after {name}\nrfc_ir: 1\nstage: ")
    assert result.stdout.count("# IR after") == 1


def test_dump_ir_after_an_unknown_pass_is_bad_usage(tmp_path):
    result = run_rfc("build", LISTING_1, "-o", tmp_path / "out", "--dump-ir-after", "expand")
    assert result.returncode == 2
    words = " ".join(result.stderr.replace("│", " ").split())
    assert "'expand' is not a pass; choose from parse, resolve-types," in words
    assert not (tmp_path / "out").exists()


def test_rebuild_replaces_the_last_builds_files_only(tmp_path):
    out = tmp_path / "out"
    assert run_rfc("build", LISTING_1, "-o", out, "--emit-ir").returncode == 0
    (out / "notes.vhd").write_text("-- the user's own\n")
    assert run_rfc("build", LISTING_1, "-o", out).returncode == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == [
        ".rfc-build", "build.sh", "hls", "hw", "notes.vhd", "report.md", "sw", "vivado"
    ]  # fmt: skip
    assert not (out / "model.yaml").exists()
    assert (out / "notes.vhd").read_text() == "-- the user's own\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_a_spec_kept_inside_the_output_survives_a_rebuild(tmp_path):
    out = tmp_path / "out"
    assert run_rfc("build", LISTING_1, "-o", out).returncode == 0
    inputs = [p for p in LISTING_1.parent.iterdir() if p.is_file()]
    for given in inputs:
        (out / given.name).write_bytes(given.read_bytes())
    result = run_rfc("build", out / LISTING_1.name, "-o", out)
    assert result.returncode == 0, result.stderr
    for given in inputs:
        assert (out / given.name).read_bytes() == given.read_bytes()


def test_a_directory_named_like_the_marker_does_not_make_a_directory_rfcs(tmp_path):
    (tmp_path / ".rfc-build").mkdir()
    mine = tmp_path / "notes.txt"
    mine.write_text("keep me\n")
    result = run_rfc("build", LISTING_1, "-o", tmp_path)
    assert result.returncode == 1
    assert "holds files that rfc build did not write; refusing to replace it" in result.stderr
    assert mine.read_text() == "keep me\n"


def test_build_never_replaces_a_directory_it_did_not_write(tmp_path):
    mine = tmp_path / "notes.txt"
    mine.write_text("keep me\n")
    result = run_rfc("build", LISTING_1, "-o", tmp_path)
    assert result.returncode == 1
    assert "holds files that rfc build did not write; refusing to replace it" in result.stderr
    assert mine.read_text() == "keep me\n"


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("missing.yaml", "error: spec 'missing.yaml' does not exist"),
        ("spec.toml", "error: spec 'spec.toml' is neither YAML nor Python"),
    ],
)
def test_specs_that_cannot_be_read(tmp_path, spec, message):
    (tmp_path / "spec.toml").write_text("[project]\n")
    result = run_rfc("check", spec, cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.startswith(message)
