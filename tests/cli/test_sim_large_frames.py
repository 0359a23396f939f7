"""A frame of several megabytes goes through the simulated logic whole, in bounded time.

One 1024x768 rgb8 image (2.36 MB serialized) through a pass-through system on the default
simulator: the subscriber's frame guard holds the whole frame before handing it on, so the
answer begins long after the transfer ends and takes as long again. The replay must wait for
it (neither calling the logic idle nor stalled) and publish the very bytes rosbags serialized.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.lower.system.systems import PASS_THROUGH, write_spec

ROOT = Path(__file__).resolve().parents[2]
IMAGE = "sensor_msgs/msg/Image"
SPEC = """
project: {name: BigImage, fpgaPart: xczu9eg-ffvb1156-2-e, middleware: ROS2, busWidth: 64,
  scheduler: LRU, maxima: {string: 16, fields: {data: 2359296}}}
accelerators:
  - name: PassImage
    type: MyHDL
    sources: ./pass.py
    top: pass_through
    interface:
      input: [{message: sensor_msgs/Image}]
      output: [{message: sensor_msgs/Image}]
blocks:
  - {name: image_sub, type: ROS>accelerator, message: sensor_msgs/Image, topic: /camera/image,
     outgoing: [{name: pass}]}
  - {name: pass, type: PassImage, outgoing: [{name: image_pub}]}
  - {name: image_pub, type: accelerator>ROS, message: sensor_msgs/Image, topic: /camera/out}
"""


@pytest.mark.slow
def test_a_two_megabyte_image_passes_through_the_logic_byte_exact(tmp_path, monkeypatch):
    spec = write_spec(tmp_path, SPEC, pass__py=PASS_THROUGH)
    types = message_types("ros2")
    pixels = np.random.default_rng(15).integers(0, 256, 1024 * 768 * 3, dtype=np.uint8)
    image = {
        "header": {"stamp": {"sec": 1, "nanosec": 2}, "frame_id": "camera"},
        "height": 768,
        "width": 1024,
        "encoding": "rgb8",
        "is_bigendian": 0,
        "step": 3 * 1024,
        "data": pixels,
    }
    data = types.serialize(types.build(IMAGE, image), IMAGE)
    assert len(data) > 2 * 1024 * 1024
    bag, out = tmp_path / "in.mcap", tmp_path / "out.mcap"
    write_bag(bag, types, {"/camera/image": IMAGE}, [("/camera/image", 1000, data)])
    # a long replay: the model at g++'s default level, not the suite's -O0 (21.5 s there, 13.5 s)
    monkeypatch.delenv("RFC_VERILATOR_OPT", raising=False)
    result = subprocess.run(
        [sys.executable, "-m", "rfc", "sim", spec, "--bag", bag, "--out", out, "--json"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=900,  # the model's compilation included; the replay itself takes seconds
        check=False,
    )
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert account["published"] == {"/camera/out": 1}
    assert account["dropped"] == []
    (published,) = read_bag(out, types)
    assert published.data == data
