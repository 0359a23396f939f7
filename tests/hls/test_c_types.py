"""The HLS header and stub: structs that mirror the selected fields, and that g++ compiles."""

from __future__ import annotations

import subprocess
from importlib import resources
from pathlib import Path

import pytest

from rfc.errors import RfcError
from rfc.hls.c_types import hls_header, hls_stub, message_struct, message_structs
from rfc.ir.model import Direction
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side, accelerator_signature
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import message_types
from rfc.messages.selection import select
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
FRANKA_MSGS = str(ROOT / "examples" / "franka" / "msg")
INCLUDE = Path(str(resources.files("rfc.lib").joinpath("hls/include")))


def signature(types, message: str, port: str, output: bool, include=()):
    layout = flatten(types, message)
    if include:
        layout = select(layout, include)
    side = Side.PUBLISHER if output else Side.SUBSCRIBER
    return accelerator_signature(plan(layout, 64, Limits()), side, port)


def compiles(directory: Path, name: str, header: str, stub: str) -> subprocess.CompletedProcess:
    (directory / f"{name}_messages.h").write_text(header)
    (directory / f"{name}.cpp").write_text(stub)
    flags = ["-std=c++14", "-fsyntax-only", "-Wall", "-Wextra", "-Werror"]
    flags += ["-Wno-unknown-pragmas", "-Wno-unused-parameter"]
    command = ["g++", *flags, f"-I{directory}", f"-I{INCLUDE}", str(directory / f"{name}.cpp")]
    return subprocess.run(command, capture_output=True, text=True, check=False)


CASES = {
    "image": ("ros2", "sensor_msgs/msg/Image", ("header", "height", "width", "data")),
    "polygon": ("ros2", "geometry_msgs/msg/PolygonStamped", ()),
    "triangle": ("ros2", "shape_msgs/msg/MeshTriangle", ()),
    "franka": (
        "ros1",
        "franka_msgs/msg/FrankaState",
        ("header", "q", "q_d", "O_T_EE", "O_T_EE_d", "F_T_EE"),
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_header_and_the_stub_compile(tmp_path, case):
    middleware, message, include = CASES[case]
    types = message_types(middleware, msg_paths=(FRANKA_MSGS,))
    ports = {
        "a": signature(types, message, "a", False, include),
        "b": signature(types, message, "b", True, include),
    }
    structs = message_structs(ports, {"a": Direction.IN, "b": Direction.OUT})
    header = hls_header("Acc", structs)
    stub = hls_stub("Acc", structs)
    result = compiles(tmp_path, "Acc", header, stub)
    assert result.returncode == 0, result.stderr + header


def test_fields_become_nested_structs_c_arrays_and_streams_with_their_length():
    types = message_types("ros2")
    ports = {
        "poly": signature(types, "geometry_msgs/msg/PolygonStamped", "poly", False),
        "tri": signature(types, "shape_msgs/msg/MeshTriangle", "tri", True),
    }
    structs = message_structs(ports, {"poly": Direction.IN, "tri": Direction.OUT})
    header = hls_header("Shapes", structs)
    assert "struct poly_header_t {\n    poly_header_stamp_t stamp;\n" in header
    assert "    uint32_t frame_id_length;  // string\n" in header
    assert "struct poly_polygon_t {\n    uint32_t points_length;" in header
    assert "struct poly_polygon_points_t {\n    float x;  // float32\n" in header
    assert "    uint32_t vertex_indices[3];  // uint32\n" in header
    assert (
        "void Shapes(\n    poly_t poly,\n    hls::stream<char> &poly_header_frame_id,\n"
        "    hls::stream<poly_polygon_points_t> &poly_polygon_points,\n    tri_t *tri);"
    ) in header


def test_the_stub_comments_every_field_with_its_ros_type():
    types = message_types("ros2")
    ports = {"rgb": signature(types, "sensor_msgs/msg/Image", "rgb", False, ("height", "data"))}
    stub = hls_stub("Gray", message_structs(ports, {"rgb": Direction.IN}))
    assert "//   rgb.height: uint32 (height)" in stub
    assert "//   rgb_data: read rgb.data_length elements of uint8_t (data: uint8[])" in stub
    assert "#pragma HLS INTERFACE mode=ap_fifo port=rgb_data" in stub


def test_a_sequence_of_strings_is_refused_with_a_hint():
    types = message_types("ros2")
    ports = signature(types, "sensor_msgs/msg/JointState", "joints", False)
    with pytest.raises(RfcError) as error:
        message_struct("joints", ports, output=False)
    assert "carries a sequence of strings ('name')" in str(error.value)
    assert "exclude 'name' from port 'joints'" in str(error.value)


def test_a_field_named_like_a_cpp_keyword_is_refused(tmp_path):
    package = tmp_path / "rfc_keywords" / "msg"
    package.mkdir(parents=True)
    (package / "Keywords.msg").write_text("int32 new\nint32 old\n")
    types = message_types("ros2", msg_paths=(str(tmp_path),))
    ports = signature(types, "rfc_keywords/msg/Keywords", "k", False)
    with pytest.raises(RfcError) as error:
        message_struct("k", ports, output=False)
    assert "is named 'new', a C++ keyword" in str(error.value)


def test_rfc_build_writes_the_header_the_example_sources_compile_against(tmp_path):
    spec = ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml"
    result = run_rfc("build", spec, "-o", tmp_path / "build", "--no-hardware", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    for name, source in [
        ("RgbToGray", "rgb_to_gray.cpp"),
        ("Downscale", "downscale.cpp"),
        ("IntegralImage", "integral_image.cpp"),
    ]:
        header = tmp_path / "build" / "hls" / f"{name}_messages.h"
        assert header.exists()
        flags = ["-std=c++14", "-fsyntax-only", "-Wall", "-Werror", "-Wno-unknown-pragmas"]
        command = ["g++", *flags, f"-I{header.parent}", f"-I{INCLUDE}", str(spec.parent / source)]
        compiled = subprocess.run(command, capture_output=True, text=True, check=False)
        assert compiled.returncode == 0, compiled.stderr
