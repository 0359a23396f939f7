"""Whole-system generation: rfc build's logic elaborates, its scripts hold together, its errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from rfc.toolchain import analyze
from tests.lower.system.systems import PASS_THROUGH, fan_out, point_system, point_vhdl, write_spec
from tests.support.cli import run_rfc
from tests.support.vendor_check import check_vivado, run_script

ROOT = Path(__file__).resolve().parents[3]
TWIST = "geometry_msgs/msg/Twist"


def build(spec: Path, out: Path) -> None:
    result = run_rfc("build", spec, "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr


def refused(spec: Path, out: Path) -> str:
    result = run_rfc("build", spec, "-o", out, cwd=ROOT)
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert not out.exists()
    return result.stderr


def logic_files(out: Path) -> list[Path]:
    return [out / "hw" / name for name in (out / "hw/files.txt").read_text().split()]


@pytest.mark.parametrize(
    ("spec", "top", "elaborates"),
    [
        ("quaternion_to_euler/project.yaml", "quaternion_to_euler_pl", True),
        # strings and sequences: publishers with their buffers
        ("multi_type/MultiType.yaml", "multi_type_pl", True),
        # an HLS core's VHDL comes from Vitis HLS: the rest analyses, the whole cannot elaborate
        ("rotation_converter/RotationConverterNode.yaml", "rotation_converter_node_pl", False),
    ],
)
def test_an_example_builds_into_logic_ghdl_accepts_and_vivado_scripts_that_hold(
    tmp_path, spec, top, elaborates
):
    out = tmp_path / "build"
    build(ROOT / "examples" / spec, out)
    files = logic_files(out)
    assert files[-1].name == f"{top}.vhd"
    analyze(files, tmp_path / "work", top if elaborates else None)
    record = run_script(out / "vivado/build.tcl", tmp_path / "vivado.log")
    cells = check_vivado(record)
    assert "manager" in cells
    hls_runs = sorted(out.glob("hls/*/run.tcl"))
    assert bool(hls_runs) is not elaborates
    for run in hls_runs:
        hls = run_script(run, tmp_path / "hls.log")
        assert hls.of("set_top") == [[["QuaternionToEuler"]]]
        (source,) = hls.of("add_files")
        assert Path(source[0][0]).is_file()
        created = {(kind[0], what[0]) for kind, what, _ in record.of("create_bd_cell")}
        assert ("ip", "xilinx.com:hls:QuaternionToEuler:1.0") in created


def test_one_message_feeding_two_blocks_reaches_both(tmp_path):
    spec = write_spec(tmp_path, fan_out(), pass__py=PASS_THROUGH)
    types = message_types("ros2")
    inputs = [
        types.serialize(
            types.build(
                TWIST,
                {
                    "linear": {"x": float(i), "y": -1.5, "z": 0.0},
                    "angular": {"x": 1e300, "y": -0.0, "z": i / 7},
                },
            ),
            TWIST,
        )
        for i in range(12)
    ]
    bag = tmp_path / "in.mcap"
    # close together, so a message waits while the one before is taken by only one block
    write_bag(bag, types, {"/cmd": TWIST}, [("/cmd", 100 * i, d) for i, d in enumerate(inputs)])
    result = run_rfc("sim", spec, "--bag", bag, "--out", tmp_path / "o.mcap", "--json", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["published"] == {"/a": 12, "/b": 12}
    out = list(read_bag(tmp_path / "o.mcap", types))
    for topic in ("/a", "/b"):
        assert [m.data for m in out if m.topic == topic] == inputs


def test_a_vhdl_accelerator_on_the_convention_is_instantiated(tmp_path):
    spec = write_spec(
        tmp_path, point_system("VHDL", "pass.vhd", "pass_point"), pass__vhd=point_vhdl()
    )
    build(spec, tmp_path / "build")
    files = logic_files(tmp_path / "build")
    assert "pass.vhd" in [f.name for f in files]
    analyze(files, tmp_path / "work", "point_system_pl")


def test_a_vhdl_accelerator_off_the_convention_is_refused_port_by_port(tmp_path):
    spec = write_spec(
        tmp_path, point_system("VHDL", "pass.vhd", "pass_point"), pass__vhd=point_vhdl(x_bits=32)
    )
    message = refused(spec, tmp_path / "build")
    assert "spec.yaml:" in message
    assert "in0_x is in 32-bit vector, expected in std_logic_vector(63 downto 0)" in message


def test_a_missing_vhdl_entity_is_refused(tmp_path):
    spec = write_spec(tmp_path, point_system("VHDL", "pass.vhd", "no_such"), pass__vhd=point_vhdl())
    assert "no entity 'no_such'" in refused(spec, tmp_path / "build")


def test_a_myhdl_block_without_the_message_ports_is_refused_with_the_signature_to_write(
    tmp_path,
):
    block = "from myhdl import block\n\n@block\ndef acc(clk, rst, a, b):\n    return []\n"
    spec = write_spec(tmp_path, point_system("MyHDL", "acc.py", "acc"), acc__py=block)
    message = refused(spec, tmp_path / "build")
    assert "it lacks in0_valid, in0_ready, in0_x" in message
    assert "it also needs a, b" in message
    assert "acc(clk, rst, in0, out0) taking one interface object per message port" in message
    assert "acc(clk, rst, in0_valid, in0_ready, in0_x, in0_y, in0_z, out0_valid" in message


def test_an_hls_function_with_the_wrong_arguments_is_refused_at_its_line(tmp_path):
    cpp = "void Pass(double x, double y, double *a) {\n  *a = x + y;\n}\n"
    spec = write_spec(tmp_path, point_system("HLS", "pass.cpp", "Pass"), pass__cpp=cpp)
    message = refused(spec, tmp_path / "build")
    assert "has 3 arguments; its messages need 6" in message
    assert "pass.cpp:1" in message


def test_the_report_gives_latencies_against_targets_and_estimated_resources(
    tmp_path, synthesis_cache
):
    spec = write_spec(tmp_path, fan_out(), pass__py=PASS_THROUGH)  # LST
    cache = {"RFC_CACHE_DIR": str(synthesis_cache)}  # the session's, not the user's ~/.cache
    result = run_rfc("build", spec, "-o", tmp_path / "build", "--estimate", cwd=ROOT, env=cache)
    assert result.returncode == 0, result.stderr
    report = (tmp_path / "build/report.md").read_text()
    rows = {
        tuple(cell.strip(" `") for cell in line.split("|")[1:3]): line.split("|")[3:5]
        for line in report.split("## Latencies")[1].split("## Resources")[0].splitlines()
        if line.startswith("| ") and "---" not in line and "block" not in line
    }
    # Twist: 52 bytes of CDR frame on a 32-bit bus is 13 beats
    assert [c.strip() for c in rows[("subscriber", "twist_sub")]] == ["15", "≤ 15"]
    assert int(rows[("publisher", "first_pub")][0]) <= 16
    assert rows[("accelerator", "first")][0].strip() == "1"
    resources = report.split("## Resources")[1]
    lut = int(next(line for line in resources.splitlines() if "fan_out_pl" in line).split("|")[2])
    assert 100 < lut < 5000


def test_estimating_a_logic_with_hls_cores_is_refused(tmp_path, synthesis_cache):
    spec = ROOT / "examples/rotation_converter/RotationConverterNode.yaml"
    cache = {"RFC_CACHE_DIR": str(synthesis_cache)}
    result = run_rfc("build", spec, "-o", tmp_path / "b", "--estimate", cwd=ROOT, env=cache)
    assert result.returncode == 1
    assert "its HLS cores come from Vitis HLS" in result.stderr
    assert not (tmp_path / "b").exists()


def test_buffers_beyond_the_parts_block_ram_are_refused_naming_the_largest(tmp_path):
    source = ROOT / "examples/multi_type"
    for name in ("MultiType.yaml", "passthrough.py"):
        text = (source / name).read_text()
        if name.endswith(".yaml"):  # back to the default maxima
            text = "\n".join(line for line in text.splitlines() if "maxima:" not in line)
        (tmp_path / name).write_text(text)
    message = refused(tmp_path / "MultiType.yaml", tmp_path / "b")
    # 1,028 for the publishers' buffers (the last streams go through), 1,031 for the frame guards
    assert "the logic's buffers need 2,059 block RAMs of 36 Kb at the project's maxima" in message
    assert "more than the xc7z020clg400-1's 140; the largest is the frame guard of 'Scan_sub'" in (
        message
    )
    assert "maxima: {string: 64, sequence: 4096}" in message
