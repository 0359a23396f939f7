"""verify(): each stage's invariants hold after the real passes and fail on broken designs."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from rfc.driver import compile_spec
from rfc.ir.model import Stage
from rfc.ir.verify import IrInvariantError, verify
from rfc.passes.pipeline import MODEL_PIPELINE, run_pipeline
from rfc.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
IMAGE = ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml"


@pytest.fixture(scope="module")
def derived():
    return compile_spec(IMAGE, pipeline=MODEL_PIPELINE)  # the model; its logic is refused


def test_the_pipeline_output_verifies(derived):
    assert derived.stage is Stage.DERIVED
    verify(derived)


def test_a_node_without_location_is_rejected(derived):
    block = replace(derived.blocks[0], location=None)
    with pytest.raises(IrInvariantError, match="no source location"):
        verify(replace(derived, blocks=(block, *derived.blocks[1:])))


def test_an_unresolved_endpoint_is_rejected_once_connected(derived):
    broken = replace(
        derived.connections[0], destination=replace(derived.connections[0].destination, port=None)
    )
    design = replace(derived, connections=(broken, *derived.connections[1:]))
    with pytest.raises(IrInvariantError, match="has no port"):
        verify(design)
    verify(replace(design, stage=Stage.TYPED, infrastructure=None))  # fine before connecting


def test_an_input_fed_twice_is_rejected(derived):
    design = replace(derived, connections=(*derived.connections, derived.connections[-1]))
    with pytest.raises(IrInvariantError, match="is fed 2 times"):
        verify(design)


def test_selection_must_match_what_the_input_is_fed(derived):
    connection = replace(derived.connections[0], fields=("height",))
    with pytest.raises(IrInvariantError, match="selects other fields than it is fed"):
        verify(replace(derived, connections=(connection, *derived.connections[1:])))


def test_scheduler_needs_one_input_per_publisher(derived):
    infrastructure = derived.infrastructure
    scheduler = replace(infrastructure.scheduler, inputs=())
    broken = replace(derived, infrastructure=replace(infrastructure, scheduler=scheduler))
    with pytest.raises(IrInvariantError, match="one input per publisher"):
        verify(broken)


def test_run_pipeline_verifies_after_every_pass():
    class Sloppy:
        name = "sloppy"

        def apply(self, design):
            return replace(design, stage=Stage.DERIVED)  # claims work it did not do

    with pytest.raises(IrInvariantError):
        run_pipeline(load_spec(IMAGE), (Sloppy(),))
