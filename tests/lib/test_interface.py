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

from rfc.errors import RfcError
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side, accelerator_signature, check_names
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.interface import interface_object
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import (
    MessageTypes,
    Middleware,
    message_types,
    read_bag,
    write_bag,
)
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


KINDS = """\
bool flag
int8 i8
uint8 u8
int16 i16
uint16 u16
int32 i32
uint32 u32
int64 i64
uint64 u64
float32 f32
float64 f64
string label
uint16[3] fixed
float32[] samples
kinds_msgs/Point[2] corners
kinds_msgs/Point[] path
string[] tags
kinds_msgs/Point centre
uint8 from
"""


@pytest.fixture(scope="module")
def kinds_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("msgs")
    (folder / "kinds_msgs" / "msg").mkdir(parents=True)
    (folder / "kinds_msgs" / "msg" / "Kinds.msg").write_text(KINDS)
    (folder / "kinds_msgs" / "msg" / "Point.msg").write_text("float64 x\nint32 y\n")
    return folder


@pytest.fixture(scope="module")
def kinds_types(kinds_folder):
    return {
        middleware: MessageTypes(middleware, msg_paths=[kinds_folder])
        for middleware in (Middleware.ROS1, Middleware.ROS2)
    }


def kinds_interface(types, width, side=Side.SUBSCRIBER):
    layout = flatten(types, "kinds_msgs/msg/Kinds")
    signature = accelerator_signature(plan(layout, width, Limits()), side, "k")
    return interface_object(signature, port_signals(signature), "port k")


@pytest.mark.parametrize("width", [8, 32, 64])
@pytest.mark.parametrize("middleware", [Middleware.ROS1, Middleware.ROS2])
def test_the_interface_object_mirrors_every_field_kind(kinds_types, middleware, width):
    k, arrays = kinds_interface(kinds_types[middleware], width)
    assert [len(k.flag), len(k.i8), len(k.u16), len(k.i64), len(k.f32), len(k.f64)] == [
        1, 8, 16, 64, 32, 64]  # fmt: skip
    assert isinstance(k.flag.val, bool)
    assert [len(s) for s in k.fixed] == [16, 16, 16]
    beat = max(width // 8, 4)
    assert len(k.samples.data) == 8 * beat
    assert len(k.samples.keep) == beat
    for stream in (k.label, k.samples, k.tags.item):
        assert {"length", "data", "keep", "valid", "ready", "last"} <= set(vars(stream))
    assert [len(c.x) for c in k.corners] == [64, 64]
    assert len(k.corners[1].y) == 32
    assert {"length", "valid", "ready", "last", "x", "y"} <= set(vars(k.path))
    assert {"length", "valid", "ready", "last", "item"} <= set(vars(k.tags))
    assert len(k.centre.x) == 64
    assert len(k.from_) == 8  # a Python keyword gets PEP 8's trailing underscore
    assert {"valid", "ready"} <= set(vars(k))
    assert "error" not in vars(k)
    assert [a.elements for a in arrays] == [k.fixed]  # lists of signals copy their pins


def test_an_output_interface_object_has_the_publisher_side_handshakes(kinds_types):
    k, _ = kinds_interface(kinds_types[Middleware.ROS2], 64, Side.PUBLISHER)
    assert {"length", "data", "valid", "ready"} <= set(vars(k.samples))
    assert "keep" not in vars(k.samples)
    assert "last" not in vars(k.path)


@pytest.mark.parametrize("name", ["valid", "ready"])
def test_a_field_named_like_a_handshake_is_refused_naming_it(tmp_path, name):
    folder = tmp_path / "clash_msgs" / "msg"
    folder.mkdir(parents=True)
    (folder / "Clash.msg").write_text(f"float64 x\nbool {name}\n")
    types = MessageTypes(Middleware.ROS2, msg_paths=[tmp_path])
    with pytest.raises(RfcError) as caught:
        check_names(plan(flatten(types, "clash_msgs/msg/Clash"), 64, Limits()))
    message = str(caught.value)
    assert f"field '{name}' of clash_msgs/msg/Clash" in message
    assert f"the {name} of the message" in message
    assert f"exclude '{name}'" in message


UNDRIVEN = """
from myhdl import always_seq, block

import rfc


@rfc.accelerator(inputs={"p": "geometry_msgs/Point"}, outputs={"m": "geometry_msgs/Point"})
@block
def forgetful(clk, rst, p, m):
    @always_seq(clk.posedge, reset=rst)
    def logic():
        p.ready.next = 1
        m.valid.next = p.valid
        m.x.next = p.x
        m.y.next = p.y

    return logic


project = rfc.Project("Forgetful", middleware="ROS2", bus_width=64)
project.subscriber("sub", "geometry_msgs/Point") >> project.accelerator("acc", forgetful) >> (
    project.publisher("pub", "geometry_msgs/Point")
)
"""


def test_an_output_the_block_never_drives_is_refused_by_its_member(tmp_path):
    spec = tmp_path / "forgetful.py"
    spec.write_text(UNDRIVEN)
    result = run_rfc("build", spec, "-o", tmp_path / "out")
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert "MyHDL accelerator 'forgetful' never drives m.z (port m_z)" in result.stderr
    assert "m.z.next = 0" in result.stderr
    assert not (tmp_path / "out").exists()


EVERY_KIND = """
project: {{name: Kinds, middleware: {middleware}, busWidth: {width}, scheduler: LRU,
          msg_paths: [{msgs}], maxima: {{string: 24, sequence: 6}}}}
accelerators:
  - name: PassKinds
    type: MyHDL
    sources: ./pass.py
    top: typed_pass_through
    interface:
      input: [{{message: kinds_msgs/Kinds}}]
      output: [{{message: kinds_msgs/Kinds}}]
blocks:
  - {{name: sub, type: ROS>accelerator, message: kinds_msgs/Kinds, topic: /in,
     outgoing: [{{name: acc}}]}}
  - {{name: acc, type: PassKinds, outgoing: [{{name: pub}}]}}
  - {{name: pub, type: accelerator>ROS, message: kinds_msgs/Kinds, topic: /out}}
"""


def kinds(rng: np.random.Generator) -> dict:
    def text() -> str:
        return "".join(rng.choice(list("abcxyz_/"), size=int(rng.integers(0, 25))))

    def point() -> dict:
        return {"x": float(rng.normal()), "y": int(rng.integers(-(2**31), 2**31))}

    integers = {f"{s}{b}": int(rng.integers(-(2 ** (b - 1)), 2 ** (b - 1))) for s, b in
                (("i", 8), ("i", 16), ("i", 32), ("i", 64))}  # fmt: skip
    integers |= {f"u{b}": int(rng.integers(0, 2**b, dtype=np.uint64)) for b in (8, 16, 32, 64)}
    return integers | {
        "flag": bool(rng.integers(2)),
        "f32": float(np.float32(rng.normal())),
        "f64": float(rng.normal()),
        "label": text(),
        "fixed": [int(v) for v in rng.integers(0, 2**16, size=3)],
        "samples": rng.normal(size=int(rng.integers(0, 7))).astype(np.float32),
        "corners": [point(), point()],
        "path": [point() for _ in range(int(rng.integers(0, 7)))],
        "tags": [text() for _ in range(int(rng.integers(0, 7)))],
        "centre": point(),
        "from": int(rng.integers(0, 256)),
    }


@pytest.mark.parametrize(
    ("middleware", "width"), [(Middleware.ROS1, 8), (Middleware.ROS2, 32), (Middleware.ROS2, 64)]
)
def test_every_field_kind_passes_through_a_typed_block_byte_exact(
    tmp_path, kinds_folder, kinds_types, middleware, width
):
    types = kinds_types[middleware]
    spec = tmp_path / "kinds.yaml"
    spec.write_text(EVERY_KIND.format(middleware=middleware.value, width=width, msgs=kinds_folder))
    (tmp_path / "pass.py").write_text("from rfc.lib.passthrough import typed_pass_through\n")
    rng = np.random.default_rng(width)
    kind = "kinds_msgs/msg/Kinds"
    frames = [types.serialize(types.build(kind, kinds(rng)), kind) for _ in range(10)]
    bag = tmp_path / ("in.bag" if middleware is Middleware.ROS1 else "in.mcap")
    out = bag.with_stem("out")
    write_bag(bag, types, {"/in": kind}, [("/in", 1000 * i, f) for i, f in enumerate(frames, 1)])
    result = run_rfc("sim", spec, "--bag", bag, "--out", out, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert [m.data for m in read_bag(out, types, ["/out"])] == frames
