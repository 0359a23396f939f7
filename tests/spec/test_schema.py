"""docs/spec.schema.json is the front-end's own format table, and agrees with the front-end."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
from ruamel.yaml import YAML

from rfc.spec.schema import json_schema

ROOT = Path(__file__).resolve().parents[2]
SCHEMA_FILE = ROOT / "docs" / "spec.schema.json"
GOOD_SPECS = [
    ROOT / "examples" / "rotation_converter" / "RotationConverterNode.yaml",
    ROOT / "examples" / "image_pipeline" / "ImagePipeline.yaml",
    Path(__file__).parent / "systems" / "quat_myhdl.yaml",
]
CATALOGUE = Path(__file__).parent / "catalogue"


def load(path):
    return YAML(typ="safe", pure=True).load(path.read_text())


def test_schema_file_is_generated_from_the_format_table():
    assert json.loads(SCHEMA_FILE.read_text()) == json_schema(), (
        "regenerate with: python -m rfc.spec.schema > docs/spec.schema.json"
    )


def test_schema_is_a_valid_json_schema():
    jsonschema.Draft202012Validator.check_schema(json_schema())


@pytest.mark.parametrize("path", GOOD_SPECS, ids=lambda p: p.name)
def test_good_specs_satisfy_the_schema(path):
    jsonschema.validate(load(path), json_schema())


@pytest.mark.parametrize(
    "case",
    [
        "unknown_key",
        "outgoing_not_a_list",
        "bus_width_not_an_integer",
        "missing_required_key",
        "name_not_a_string",
        "unknown_accelerator_kind",
        "bus_width_not_allowed",
    ],
)
def test_shape_errors_of_the_catalogue_break_the_schema_too(case):
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(load(CATALOGUE / f"{case}.yaml"), json_schema())
