"""`rfc sim` of the image pipeline: its three HLS stages C-simulated, against NumPy."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
SPEC = ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml"
_SCRIPT = importlib.util.spec_from_file_location("make_bag", SPEC.parent / "make_bag.py")
assert _SCRIPT is not None
assert _SCRIPT.loader is not None
make_bag = importlib.util.module_from_spec(_SCRIPT)
_SCRIPT.loader.exec_module(make_bag)


def gray(rgb: np.ndarray) -> np.ndarray:
    r, g, b = (rgb[..., i].astype(np.int64) for i in range(3))
    return ((4899 * r + 9617 * g + 1868 * b + 8192) >> 14).astype(np.uint8)


def downscale(image: np.ndarray) -> np.ndarray:
    h, w = image.shape[0] // 2 * 2, image.shape[1] // 2 * 2
    blocks = image[:h, :w].astype(np.int64).reshape(h // 2, 2, w // 2, 2)
    return ((blocks.sum(axis=(1, 3)) + 2) >> 2).astype(np.uint8)


def integral(image: np.ndarray) -> np.ndarray:
    return image.astype(np.uint32).cumsum(axis=0).cumsum(axis=1).astype("<u4")


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
        expected = integral(downscale(gray(rgb)))
        assert (message.height, message.width) == expected.shape
        assert message.encoding == "32SC1"
        assert message.step == 4 * expected.shape[1]
        assert bytes(message.data) == expected.tobytes()
        assert message.header.frame_id == f"cam{index}"
        assert (message.header.stamp.sec, message.header.stamp.nanosec) == (index, 1000 * index)
