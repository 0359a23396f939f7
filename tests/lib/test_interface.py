"""Typed accelerator interfaces: a MyHDL block written against interface objects, in the logic.

The block of issue 13's example reads nested sub-message fields (``info.roi.x_offset``) and
writes a fixed array (``tri.vertex_indices[2]``); rfc's wrapper owns the flat ports. Built and
replayed through the whole generated logic in GHDL, it must give exactly its reference's
results, message by message.
"""

from __future__ import annotations

import json
import textwrap

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.support.cli import run_rfc

ROI_CENTER = '''
from myhdl import always_comb, always_seq, block

import rfc
from rfc.messages.rosbags_adapter import message_types


def center_reference(info):
    """The triangle (centre x, centre y, binning) of the region of interest."""
    roi = info.roi
    vertices = [roi.x_offset + roi.width // 2, roi.y_offset + roi.height // 2, info.binning_x]
    return message_types("ros2").build("shape_msgs/msg/MeshTriangle", {"vertex_indices": vertices})


@rfc.accelerator(
    inputs={"info": rfc.port("sensor_msgs/CameraInfo", include=["roi", "binning_x"])},
    outputs={"tri": "shape_msgs/MeshTriangle"},
    reference=center_reference,
)
@block
def roi_center(clk, rst, info, tri):
    @always_comb
    def accept():
        info.ready.next = not tri.valid

    @always_seq(clk.posedge, reset=rst)
    def compute():
        if tri.valid and tri.ready:
            tri.valid.next = 0
        if info.valid and not tri.valid:
            tri.vertex_indices[0].next = info.roi.x_offset + (info.roi.width >> 1)
            tri.vertex_indices[1].next = info.roi.y_offset + (info.roi.height >> 1)
            tri.vertex_indices[2].next = info.binning_x
            tri.valid.next = 1

    return accept, compute


project = rfc.Project("RoiCenter", middleware="ROS2", bus_width=BUS, scheduler="LRU")
camera = project.subscriber("info_sub", "sensor_msgs/CameraInfo", topic="/camera_info")
center = project.accelerator("center", roi_center)
triangle = project.publisher("tri_pub", "shape_msgs/MeshTriangle", topic="/triangle")
camera >> center >> triangle
'''


def camera_info(rng: np.random.Generator) -> dict:
    roi = {
        name: int(rng.integers(0, 2**30)) for name in ("x_offset", "y_offset", "height", "width")
    }
    return {
        "header": {"stamp": {"sec": 1, "nanosec": 2}, "frame_id": "cam" * int(rng.integers(4))},
        "height": 480,
        "width": 640,
        "distortion_model": "plumb_bob",
        "d": rng.normal(size=int(rng.integers(0, 6))),
        "k": rng.normal(size=9),
        "r": rng.normal(size=9),
        "p": rng.normal(size=12),
        "binning_x": int(rng.integers(0, 2**32)),
        "binning_y": 3,
        "roi": roi | {"do_rectify": bool(rng.integers(2))},
    }


@pytest.mark.parametrize("bus", [32, 64])
def test_a_block_on_nested_fields_and_fixed_arrays_equals_its_reference_in_ghdl(tmp_path, bus):
    spec = tmp_path / "roi.py"
    spec.write_text(textwrap.dedent(ROI_CENTER).replace("BUS", str(bus)))
    types = message_types("ros2")
    rng = np.random.default_rng(bus)
    kind = "sensor_msgs/msg/CameraInfo"
    infos = [types.build(kind, camera_info(rng)) for _ in range(12)]
    messages = [
        ("/camera_info", 1000 * (i + 1), types.serialize(m, kind)) for i, m in enumerate(infos)
    ]
    write_bag(tmp_path / "in.mcap", types, {"/camera_info": kind}, messages)

    result = run_rfc("sim", spec, "--bag", tmp_path / "in.mcap", "--out", tmp_path / "out.mcap",
                     "--json", cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)
    out = read_bag(tmp_path / "out.mcap", types, ["/triangle"])
    outputs = [types.deserialize(m.data, "shape_msgs/msg/MeshTriangle") for m in out]
    expected = [
        [
            m.roi.x_offset + m.roi.width // 2,
            m.roi.y_offset + m.roi.height // 2,
            m.binning_x,
        ]
        for m in infos
    ]
    assert [list(map(int, t.vertex_indices)) for t in outputs] == expected
