"""`rfc stub`: skeletons typed from the message signatures build as written.

A user declares an accelerator in the spec, has `rfc stub` write its source, and builds: the
skeleton must have exactly the ports `rfc build` checks, for every form (MyHDL interface
objects, VHDL flat ports, a ROS-SW function), and GHDL must accept the logic.
"""

from __future__ import annotations

import ast
import shutil
import subprocess
from pathlib import Path

import pytest

from rfc.toolchain import analyze
from tests.lower.system.hls_cores import shrink_images
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
FRANKA = """
project: {{name: Franka, middleware: ROS, busWidth: 64, msg_paths: [{msgs}]}}
accelerators:
  - name: Kinematics
    type: {kind}
    sources: ./{source}
    interface:
      input: [{{name: state, message: franka_msgs/FrankaState,
                include: [header, q, q_d, O_T_EE, O_T_EE_d, F_T_EE]}}]
      output: [{{name: pose, message: geometry_msgs/PoseStamped}}]
blocks:
  - {{name: state_sub, type: ROS>accelerator, message: franka_msgs/FrankaState,
     topic: /franka_state, outgoing: [{{name: fk}}]}}
  - {{name: fk, type: Kinematics, outgoing: [{{name: pose_pub}}]}}
  - {{name: pose_pub, type: accelerator>ROS, message: geometry_msgs/PoseStamped, topic: /pose}}
"""


def franka_spec(folder: Path, kind: str, source: str) -> Path:
    spec = folder / "franka.yaml"
    spec.write_text(FRANKA.format(msgs=ROOT / "examples/franka/msg", kind=kind, source=source))
    return spec


def stub(spec: Path, accelerator: str, language: str) -> str:
    result = run_rfc("stub", spec, accelerator, "--lang", language)
    assert result.returncode == 0, result.stderr
    return result.stdout


def built_logic(spec: Path, out: Path) -> list[Path]:
    result = run_rfc("build", spec, "-o", out)
    assert result.returncode == 0, result.stderr
    hw = out / "hw"
    return [hw / name for name in (hw / "files.txt").read_text().split()]


def test_the_myhdl_skeleton_takes_the_franka_state_as_one_argument_and_builds(tmp_path):
    spec = franka_spec(tmp_path, "MyHDL", "kinematics.py")  # the source does not exist yet
    text = stub(spec, "Kinematics", "myhdl")
    function = next(node for node in ast.parse(text).body if isinstance(node, ast.FunctionDef))
    assert [a.arg for a in function.args.args] == ["clk", "rst", "state", "pose"]
    for member in ("state.q[6]", "state.O_T_EE[15]", "state.header.frame_id.data",
                   "state.header.frame_id.length", "pose.pose.orientation.w"):  # fmt: skip
        assert f"{member}: " in text
    (tmp_path / "kinematics.py").write_text(text)
    files = built_logic(spec, tmp_path / "build")
    analyze(files, tmp_path / "work", "franka_pl")


def test_the_vhdl_skeleton_has_the_ports_the_build_checks(tmp_path):
    spec = franka_spec(tmp_path, "VHDL", "kinematics.vhd")
    text = stub(spec, "fk", "vhdl")  # a block names its type too
    assert "state_q_6 : in std_logic_vector(63 downto 0);  -- state.q[6]: float64" in text
    assert "pose_ready : in std_logic;" in text
    (tmp_path / "kinematics.vhd").write_text(text)
    files = built_logic(spec, tmp_path / "build")
    analyze(files, tmp_path / "work", "franka_pl")


def test_the_python_skeleton_is_a_ros_sw_function_that_returns_its_output(tmp_path):
    spec = franka_spec(tmp_path, "ROS-SW", "kinematics.py")
    text = stub(spec, "Kinematics", "python")
    namespace: dict = {}
    exec(compile(text, "kinematics.py", "exec"), namespace)
    pose = namespace["Kinematics"](None)
    assert pose.__msgtype__ == "geometry_msgs/msg/PoseStamped"
    assert pose.pose.orientation.w == 0.0


@pytest.mark.parametrize(
    ("name", "hint"),
    [("Kinematic", "did you mean 'Kinematics'"), ("xyz", "accelerator types: Kinematics")],
)
def test_an_unknown_accelerator_is_an_error_with_the_names_there_are(tmp_path, name, hint):
    spec = franka_spec(tmp_path, "MyHDL", "kinematics.py")
    result = run_rfc("stub", spec, name)
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert f"no accelerator type or accelerator block '{name}'" in result.stderr
    assert hint in result.stderr


def test_the_hls_skeleton_takes_the_franka_state_as_one_struct_and_compiles(tmp_path):
    spec = franka_spec(tmp_path, "HLS", "kinematics.cpp")
    text = stub(spec, "Kinematics", "hls")
    declaration = "state_t state,\n    hls::stream<char> &state_header_frame_id,"
    assert declaration in text
    assert "//   state.q[6]: float64 (q[6])" in text
    (tmp_path / "kinematics.cpp").write_text(text)
    built = run_rfc("build", spec, "-o", tmp_path / "build", "--no-hardware")
    assert built.returncode == 0, built.stderr
    header = tmp_path / "build/hls/Kinematics_messages.h"
    assert header.is_file()
    compiled = subprocess.run(
        ["g++", "-std=c++17", "-fsyntax-only", "-I", header.parent,
         "-I", ROOT / "lib/hls/include", tmp_path / "kinematics.cpp"],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert compiled.returncode == 0, compiled.stderr


#: Specs with HLS accelerators whose ports the logic takes: (folder to copy, spec, accelerator,
#: its source relative to the copy).
HLS_SPECS = {
    "sensor_hub": (ROOT / "examples/sensor_hub", "SensorHub.yaml", "StateEstimator",
                   "state_estimator.cpp"),
    "two streams in": (ROOT / "examples/image_pipeline", "ImagePipeline_hls.yaml", "RgbToGray",
                       "rgb_to_gray.cpp"),
    "one stream in": (ROOT / "tests/lower/system", "hls_invert/invert.yaml", "Invert",
                      "hls_invert/invert.cpp"),
}  # fmt: skip


@pytest.mark.parametrize("case", HLS_SPECS)
def test_each_hls_skeleton_passes_the_checks_of_the_logic(tmp_path, case):
    folder, spec, accelerator, source = HLS_SPECS[case]
    copy = tmp_path / "spec"
    shutil.copytree(folder, copy)
    shrink_images(copy / spec)  # the image pipeline's full-HD buffers do not fit the part
    (copy / source).unlink()  # written from scratch by rfc stub
    text = stub(copy / spec, accelerator, "hls")
    assert "Not for the logic" not in text
    (copy / source).write_text(text)
    checked = run_rfc("check", copy / spec)
    assert checked.returncode == 0, checked.stderr


def test_the_franka_hls_skeleton_passes_the_checks_without_frame_id(tmp_path):
    spec = franka_spec(tmp_path, "HLS", "kinematics.cpp")
    spec.write_text(spec.read_text().replace("include: [header,", "include: [header.stamp,"))
    (tmp_path / "kinematics.cpp").write_text(stub(spec, "Kinematics", "hls"))
    checked = run_rfc("check", spec)
    assert checked.returncode == 0, checked.stderr


def test_an_hls_skeleton_says_why_the_logic_refuses_its_port(tmp_path):
    # FrankaState's header.frame_id comes before q: the core would start before q is parsed
    spec = franka_spec(tmp_path, "HLS", "kinematics.cpp")
    text = stub(spec, "Kinematics", "hls")
    (tmp_path / "kinematics.cpp").write_text(text)
    checked = run_rfc("check", spec)
    assert checked.returncode == 1
    said = " ".join(line.removeprefix("// ") for line in text.splitlines()[2:6])
    assert "Not for the logic as selected: port 'state' selects 'q[0]' after its last" in said
    assert "exclude 'q' or 'header.frame_id' from port 'state'" in said
    assert "port 'state' selects 'q[0]' after its last string or sequence" in checked.stderr
