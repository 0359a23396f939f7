"""`rfc sim` of the image pipeline with its three stages in the logic (GHDL), against NumPy.

The bag comes from the example's `make_bag.py` (sizes vary from image to image, odd ones
included); the spec's maxima are full HD, so the publisher streams the pixels out while the
stages compute them, and the replay needs no more than its default quiet cycles
(`--drain-cycles`) to see every image out. The example's `compare.py` must find every output
equal to NumPy's pipeline, and this test checks the same independently: sizes, pixels,
encoding, step and headers.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag
from tests.examples.image_pipeline.example import EXAMPLE, example_module
from tests.support.cli import run_rfc

SPEC = EXAMPLE / "ImagePipeline.yaml"
make_bag = example_module("make_bag")
reference = example_module("image_reference")


def test_rfc_sim_gives_numpys_integral_images_with_the_stages_in_ghdl(tmp_path):
    images = make_bag.random_images(6, seed=11)
    assert len({image.shape for image in images}) == len(images)
    assert any(h % 2 and w % 2 for h, w, _ in (image.shape for image in images))
    bag, out = tmp_path / "images.mcap", tmp_path / "integral.mcap"
    make_bag.write_images(bag, images)
    result = run_rfc("sim", SPEC, "--bag", bag, "--out", out, "--simulator", "ghdl", "--json",
                     cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert account["warnings"] == []
    assert account["software_calls"] == {}
    assert account["from_logic"] == {"Integral_pub": len(images)}
    types = message_types("ros2")
    outputs = [types.deserialize(m.data, m.type_name) for m in read_bag(out, types)]
    assert len(outputs) == len(images)
    for index, (rgb, message) in enumerate(zip(images, outputs, strict=True)):
        expected = reference.integral(reference.downscale(reference.gray(rgb)))
        assert (message.height, message.width) == expected.shape
        assert (message.encoding, message.step) == ("32SC1", 4 * expected.shape[1])
        assert np.array_equal(np.frombuffer(bytes(message.data), "<u4"), expected.reshape(-1))
        assert message.header.frame_id == f"cam{index}"
        assert (message.header.stamp.sec, message.header.stamp.nanosec) == (index, 1000 * index)
    compare = [sys.executable, EXAMPLE / "compare.py", bag, out]
    printed = subprocess.run(compare, capture_output=True, text=True, cwd=EXAMPLE, check=False)
    assert printed.returncode == 0, printed.stdout
    assert f"{len(images)} of {len(images)} integral images equal" in printed.stdout
