"""The first accelerator in three readings: RTL VHDL = GHDL's netlist = Verilog, byte for byte.

The tutorial's points (its own `points.py`) go through `rfc sim` of `mirror.yaml` in GHDL on the
VHDL, in GHDL on GHDL's netlist and in Verilator on rfc's Verilog; the three output bags must be
identical and hold, for every point, the bytes rosbags serializes of the example's reference.
A Point is a fixed-size message: one frame size, so a handful of points is enough.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag
from tests.support.sim_readings import READINGS, replay_readings

ROOT = Path(__file__).resolve().parents[3]
EXAMPLE = ROOT / "examples/first_accelerator"
POINT = "geometry_msgs/msg/Point"


def example_module(name: str):
    """A module of the example folder, loaded from its file."""
    spec = importlib.util.spec_from_file_location(f"first_accelerator_{name}", EXAMPLE / name)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def replayed(tmp_path_factory) -> tuple[Path, dict[str, Path]]:
    """The example's points bag, and the output bag of each reading (one replay each)."""
    folder = tmp_path_factory.mktemp("mirror")
    bag = folder / "points.mcap"
    example_module("points.py").make(bag, 6)
    return bag, replay_readings(EXAMPLE / "mirror.yaml", bag, folder)


@pytest.mark.slow
@pytest.mark.parametrize("reading", ["netlist", "verilog"])
def test_every_reading_gives_the_rtls_output_bag(replayed, reading):
    _, outputs = replayed
    assert outputs[reading].read_bytes() == outputs["rtl"].read_bytes()


@pytest.mark.slow
@pytest.mark.parametrize("reading", list(READINGS))
def test_every_reading_sends_the_references_bytes(replayed, reading):
    bag, outputs = replayed
    types = message_types("ros2")
    reference = example_module("mirror.py").mirror_reference
    sent = [types.deserialize(m.data, POINT) for m in read_bag(bag, types)]
    expected = [types.serialize(reference(p), POINT) for p in sent]
    assert [m.data for m in read_bag(outputs[reading], types)] == expected
