"""generate_system: an error of the library while the logic is generated names its block."""

from __future__ import annotations

from pathlib import Path

import pytest

from rfc.driver import compile_spec
from rfc.errors import RfcError
from rfc.lower.system.generate import generate_system
from rfc.passes.pipeline import MODEL_PIPELINE

CATALOGUE = Path(__file__).parents[2] / "spec" / "catalogue"


def test_a_converter_the_library_refuses_is_located_at_its_block(tmp_path):
    # check-hardware would refuse it first; without it the lowering still says where
    spec = CATALOGUE / "field_gives_no_vhdl_port_name.yaml"
    design = compile_spec(str(spec), pipeline=MODEL_PIPELINE)
    with pytest.raises(RfcError, match="'a__b', which is not a valid VHDL identifier") as error:
        generate_system(design, tmp_path / "hw")
    block = design.block("Odd_sub")
    assert error.value.location == block.location
    assert (Path(block.location.file).name, block.location.line) == (spec.name, 7)
