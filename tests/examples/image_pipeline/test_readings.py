"""The image pipeline in three readings: RTL VHDL = GHDL's netlist = Verilog, byte for byte.

One bag from the example's `make_bag.py` goes through `rfc sim` of `ImagePipeline.yaml` in GHDL
on the VHDL, in GHDL on GHDL's netlist and in Verilator on rfc's Verilog. Eight small images of
1 to 8 pixels give `data` of 3 to 24 bytes, every length modulo the 64-bit bus; single-row ones
downscale to empty images. The three output bags must be identical and every integral image
must equal NumPy's pipeline (the example's `image_reference.py`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag
from tests.examples.image_pipeline.example import EXAMPLE, example_module
from tests.support.sim_readings import READINGS, replay_readings

#: Height by width: 1 to 8 pixels of 3 bytes, so `data` takes every length modulo 8 bytes.
SIZES = ((1, 1), (1, 2), (1, 3), (2, 2), (1, 5), (2, 3), (1, 7), (2, 4))


@pytest.fixture(scope="module")
def replayed(tmp_path_factory) -> tuple[list[np.ndarray], dict[str, Path]]:
    """The images, and the output bag of each reading (one replay each)."""
    folder = tmp_path_factory.mktemp("images")
    rng = np.random.default_rng(14)
    images = [rng.integers(0, 256, size=(h, w, 3), dtype=np.uint8) for h, w in SIZES]
    assert sorted(image.size % 8 for image in images) == list(range(8))
    bag = folder / "images.mcap"
    example_module("make_bag").write_images(bag, images)
    return images, replay_readings(EXAMPLE / "ImagePipeline.yaml", bag, folder)


@pytest.mark.slow
@pytest.mark.parametrize("reading", ["netlist", "verilog"])
def test_every_reading_gives_the_rtls_output_bag(replayed, reading):
    _, outputs = replayed
    assert outputs[reading].read_bytes() == outputs["rtl"].read_bytes()


@pytest.mark.slow
@pytest.mark.parametrize("reading", list(READINGS))
def test_every_reading_gives_numpys_integral_images(replayed, reading):
    images, outputs = replayed
    reference = example_module("image_reference")
    types = message_types("ros2")
    got = [types.deserialize(m.data, m.type_name) for m in read_bag(outputs[reading], types)]
    assert len(got) == len(images)
    for rgb, message in zip(images, got, strict=True):
        expected = reference.integral(reference.downscale(reference.gray(rgb)))
        assert (message.height, message.width) == expected.shape
        assert np.array_equal(np.frombuffer(bytes(message.data), "<u4"), expected.reshape(-1))
