"""`rfc sim` of the image pipeline: its three HLS stages C-simulated, against NumPy."""

from __future__ import annotations

import json
from pathlib import Path

from rfc.messages.rosbags_adapter import message_types, read_bag
from tests.examples.image_pipeline.example import example_module
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
SPEC = ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml"
make_bag = example_module("make_bag")
reference = example_module("image_reference")


def test_the_three_hls_stages_match_numpy_on_images_of_varying_size(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    images = make_bag.random_images(5, seed=3)
    assert len({image.shape for image in images}) > 1
    bag, out = tmp_path / "images.mcap", tmp_path / "integral.mcap"
    make_bag.write_images(bag, images)
    result = run_rfc("sim", SPEC, "--bag", bag, "--out", out, "--json", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert account["software_calls"] == {"Gray_acc": 5, "Downscale_acc": 5, "Integral_acc": 5}
    types = message_types("ros2")
    outputs = [types.deserialize(m.data, m.type_name) for m in read_bag(out, types)]
    assert len(outputs) == len(images)
    for index, (rgb, message) in enumerate(zip(images, outputs, strict=True)):
        expected = reference.pipeline(rgb)
        assert (message.height, message.width) == expected.shape
        assert message.encoding == "32SC1"
        assert message.step == 4 * expected.shape[1]
        assert bytes(message.data) == expected.tobytes()
        assert message.header.frame_id == f"cam{index}"
        assert (message.header.stamp.sec, message.header.stamp.nanosec) == (index, 1000 * index)
