"""Every example's generated VHDL is byte-identical to the digests committed beside this test.

A refactoring must leave the hardware as it was, and a build must not depend on what the process
built before; a change that means to alter it regenerates the digests with
tools/update_hdl_digests.py and says why in its commit.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from myhdl import Signal

from rfc.lib.converters.wiring import follow

ROOT = Path(__file__).resolve().parents[2]


def load_tool():
    path = ROOT / "tools" / "update_hdl_digests.py"
    spec = importlib.util.spec_from_file_location("update_hdl_digests", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


TOOL = load_tool()
RECORDED = TOOL.read_digests()
# Builds that take more than a few seconds (MyHDL converts large accelerators or many ports).
LONG = {
    "franka_fk/franka_fk.yaml",
    "franka_fk/franka_fk_ros2.yaml",
    "image_pipeline/ImagePipeline.yaml",
    "multi_type/MultiType.yaml",
    "quaternion_to_euler/project.yaml",
    "sensor_hub/SensorHub.yaml",
}


def test_every_example_spec_has_recorded_digests():
    assert sorted(RECORDED) == TOOL.example_specs()


@pytest.mark.parametrize(
    "spec", [pytest.param(s, marks=[pytest.mark.slow] if s in LONG else []) for s in RECORDED]
)
def test_the_generated_vhdl_is_byte_identical_to_the_recorded_digests(spec):
    assert TOOL.hdl_digests(spec) == RECORDED[spec]


def test_a_build_does_not_depend_on_what_the_process_built_before():
    # MyHDL numbers a block's instances by its calls in the whole process (``follow290``)
    for _ in range(3):
        follow(Signal(bool(0)), Signal(bool(0)))
    spec = "image_pipeline/ImagePipeline.yaml"
    assert TOOL.hdl_digests(spec) == RECORDED[spec]
