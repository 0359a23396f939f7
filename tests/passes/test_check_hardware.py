"""check-hardware: `rfc check` refuses what `rfc build` would, with the same words.

Each case is a spec the logic cannot be made of. Both commands must exit 1 with one message
(no traceback) naming the spec's line; `rfc build` must write nothing.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rfc.ir.infrastructure import Converter
from rfc.lib.converters.plan import plan
from rfc.lib.converters.prefix_plan import SLACK_BEATS
from rfc.lib.devices import bram36
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import select
from rfc.passes.check_hardware import subscriber_guard
from tests.lower.system.systems import PASS_THROUGH, fan_out, point_system, point_vhdl, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
CLASH = """
project: {name: Clash, middleware: ROS2, busWidth: 64, msg_paths: [./msgs]}
accelerators:
  - name: PassClash
    type: MyHDL
    sources: ./pass.py
    top: pass_through
    interface:
      input: [{message: clash_msgs/Clash}]
      output: [{message: clash_msgs/Clash}]
blocks:
  - {name: sub, type: ROS>accelerator, message: clash_msgs/Clash, outgoing: [{name: acc}]}
  - {name: acc, type: PassClash, outgoing: [{name: pub}]}
  - {name: pub, type: accelerator>ROS, message: clash_msgs/Clash}
"""
STREAM_FAN_OUT = fan_out().replace("geometry_msgs/Twist", "sensor_msgs/CompressedImage")


def multi_type_at_default_maxima(folder: Path) -> Path:
    source = ROOT / "examples/multi_type"
    for name in ("MultiType.yaml", "passthrough.py"):
        text = (source / name).read_text()
        if name.endswith(".yaml"):
            text = "\n".join(line for line in text.splitlines() if "maxima:" not in line)
        (folder / name).write_text(text)
    return folder / "MultiType.yaml"


def clash(folder: Path) -> Path:
    (folder / "msgs" / "clash_msgs" / "msg").mkdir(parents=True)
    (folder / "msgs" / "clash_msgs" / "msg" / "Clash.msg").write_text("float64 x\nbool ready\n")
    return write_spec(folder, CLASH, pass__py=PASS_THROUGH)


CASES = {
    "myhdl block off its messages": (
        lambda f: write_spec(
            f,
            point_system("MyHDL", "acc.py", "acc"),
            acc__py="from myhdl import block\n\n@block\ndef acc(clk, rst, a, b):\n    return []\n",
        ),
        "spec.yaml:4:5: MyHDL block 'acc' of accelerator 'PassPoint' does not have the ports",
    ),
    "vhdl entity off its messages": (
        lambda f: write_spec(
            f, point_system("VHDL", "p.vhd", "pass_point"), p__vhd=point_vhdl(x_bits=32)
        ),
        "in0_x is in 32-bit vector, expected in std_logic_vector(63 downto 0)",
    ),
    "a field on a handshake's member": (
        clash,
        "field 'ready' of clash_msgs/msg/Clash would be the member 'ready'",
    ),
    "strings fanned out": (
        lambda f: write_spec(f, STREAM_FAN_OUT, pass__py=PASS_THROUGH),
        "a message with strings or sequences ('header.frame_id') cannot feed several blocks",
    ),
    "hls scalar arguments off its messages": (
        lambda f: write_spec(
            f,
            point_system("HLS", "pass.cpp", "Pass"),
            pass__cpp="void Pass(double x, double *a) {}\n",
        ),
        "pass.cpp:1:11: HLS top function Pass of accelerator 'PassPoint' has 2 arguments; its "
        "messages need 6",
    ),
    "hls struct of the other port": (
        lambda f: write_spec(
            f,
            point_system("HLS", "pass.cpp", "Pass"),
            pass__cpp='#include "PassPoint_messages.h"\nvoid Pass(out0_t in0, out0_t *out0) {}\n',
        ),
        "argument 'in0' of HLS top function Pass is a out0_t; expected in0_t in0",
    ),
    "buffers beyond the block ram": (
        multi_type_at_default_maxima,
        "the logic's buffers need 2,059 block RAMs of 36 Kb at the project's maxima",
    ),
}


@pytest.mark.parametrize("case", CASES)
def test_check_refuses_what_build_refuses_with_the_same_message(tmp_path, case):
    make, expected = CASES[case]
    spec = make(tmp_path)
    checked = run_rfc("check", spec, cwd=tmp_path)
    built = run_rfc("build", spec, "-o", tmp_path / "out", cwd=tmp_path)
    for result in (checked, built):
        assert result.returncode == 1, result.stderr
        assert "Traceback" not in result.stderr
        assert expected in result.stderr
    assert checked.stderr == built.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("width", [32, 64])
def test_a_full_hd_image_subscriber_is_guarded_by_the_bytes_before_its_data(width):
    types = message_types(Middleware.ROS2)
    layout = select(flatten(types, "sensor_msgs/msg/Image"), include=["header", "width", "data"])
    limits = Limits(string=64, fields={"data": 1920 * 1080 * 3})
    converter = Converter(0, "Camera_sub", "/image", "sensor_msgs/msg/Image", layout, width,
                          None, 6_300_000)  # fmt: skip
    guard = subscriber_guard(converter, plan(layout, width, limits), limits)
    assert guard is not None
    assert guard.path == "(frame before 'data')"
    # the longest frame before data: rosbags' Image with both strings at their maximum
    tree = {"header": {"frame_id": "f" * 64}, "encoding": "e" * 64}
    longest = types.build("sensor_msgs/msg/Image", tree)
    prefix = len(types.serialize(longest, "sensor_msgs/msg/Image"))
    assert guard.words >= -(-prefix // (width // 8)) + SLACK_BEATS  # and the checker's slack
    assert bram36(guard.bits, guard.words) == 1


def test_only_a_myhdl_producer_streams_its_image_through_the_publisher():
    # the same full-HD system: MyHDL stages are record-first, HLS cores are not
    example = ROOT / "examples/image_pipeline"
    assert run_rfc("check", example / "ImagePipeline.yaml", cwd=example).returncode == 0
    refused = run_rfc("check", example / "ImagePipeline_hls.yaml", cwd=example)
    assert refused.returncode == 1
    assert "the largest holds 'data' of 'Integral_pub' (1,519)" in refused.stderr
