"""hw/verilog/: the logic in Verilog beside its VHDL, and --estimate on it."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from rfc.toolchain import read_entities
from tests.lower.system.systems import point_system, point_vhdl, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
QUATERNION = ROOT / "examples/quaternion_to_euler"


def verilog_modules(files: list[Path], top: str, workdir: Path) -> dict[str, dict[str, tuple]]:
    """Each module of a Verilog design below `top` as Yosys reads it: port → (direction, bits).

    Yosys elaborates the hierarchy first, so a missing module or port fails here.
    """
    out = workdir / "design.json"
    script = (
        f"read_verilog {' '.join(map(str, files))}; hierarchy -check -top {top}; proc; "
        f"write_json {out}"
    )
    result = subprocess.run(
        [shutil.which("yosys") or "yosys", "-q", "-p", script],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    modules = json.loads(out.read_text())["modules"]
    return {
        name: {p: (v["direction"], len(v["bits"])) for p, v in module["ports"].items()}
        for name, module in modules.items()
    }


def vhdl_ports(path: Path, workdir: Path) -> dict[str, dict[str, tuple]]:
    """Each entity of a VHDL file as GHDL's parser reads it: port → (direction, bits).

    Only the entity declarations are read (without MyHDL's package, which ports do not need).
    """
    alone = workdir / path.name
    declarations = re.split(r"^architecture ", path.read_text(), flags=re.M | re.I)[0]
    lines = declarations.splitlines()
    alone.write_text("\n".join(line for line in lines if "work.pck_myhdl" not in line))
    return {
        entity.name: {p.name: (f"{p.mode}put", p.bits) for p in entity.ports}
        for entity in read_entities(alone)
    }


def listed(folder: Path) -> list[Path]:
    return [folder / name for name in (folder / "files.txt").read_text().split()]


def test_every_vhdl_entity_has_a_verilog_module_with_the_same_ports(tmp_path):
    out = tmp_path / "build"
    result = run_rfc("build", QUATERNION / "project.yaml", "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    verilog = listed(out / "hw/verilog")
    assert verilog[-1].name == "quaternion_to_euler_pl.v"
    modules = verilog_modules(verilog, "quaternion_to_euler_pl", tmp_path)
    entities = {}
    for vhdl in listed(out / "hw")[1:]:  # MyHDL's package first
        entities.update(vhdl_ports(vhdl, tmp_path))
    # besides the entities: the core's rfc.lib blocks, each a module of its own, once
    separate = set(modules) - set(entities)
    assert {name.rsplit("_", 1)[0] for name in separate} == {
        "float_to_fixed_pipeline",
        "exact_multiply",
        "cordic_pipeline",
        "fixed_to_float_pipeline",
    }
    assert set(entities) <= set(modules)
    for name, ports in entities.items():
        assert modules[name] == ports, name
    report = (out / "report.md").read_text()
    assert "| `QuaternionToEuler` | MyHDL | MyHDL's Verilog back-end |" in report
    cordic = next(name for name in separate if name.startswith("cordic"))
    assert f"`{cordic}` x3 in `quaterniontoeuler`" in report


def test_a_vhdl_accelerator_gets_ghdls_netlist_and_the_report_says_so(tmp_path):
    synthesizable = point_vhdl().replace("  out0_x <= (others => '0');\n", "")
    spec = write_spec(
        tmp_path, point_system("VHDL", "pass.vhd", "pass_point"), pass__vhd=synthesizable
    )
    out = tmp_path / "build"
    result = run_rfc("build", spec, "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    verilog = listed(out / "hw/verilog")
    assert "pass_point.v" in [f.name for f in verilog]
    modules = verilog_modules(verilog, "point_system_pl", tmp_path)
    assert modules["pass_point"] == vhdl_ports(tmp_path / "pass.vhd", out)["pass_point"]
    assert "| `PassPoint` | VHDL | GHDL's synthesized netlist |" in (
        (out / "report.md").read_text()
    )


def test_a_vhdl_accelerator_ghdl_cannot_synthesize_stays_vhdl_and_is_not_estimated(tmp_path):
    # two drivers of out0_x: GHDL's synthesis refuses it, its simulation does not
    spec = write_spec(
        tmp_path, point_system("VHDL", "pass.vhd", "pass_point"), pass__vhd=point_vhdl()
    )
    result = run_rfc("build", spec, "-o", tmp_path / "build", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert "pass_point.v" not in (tmp_path / "build/hw/verilog/files.txt").read_text()
    assert "| `PassPoint` | VHDL | none: stays VHDL |" in (
        (tmp_path / "build/report.md").read_text()
    )
    result = run_rfc("build", spec, "-o", tmp_path / "estimated", "--estimate", cwd=ROOT)
    assert result.returncode == 1
    assert "GHDL could not synthesize pass_point, which stays VHDL" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "estimated").exists()


@pytest.mark.slow
@pytest.mark.parametrize(
    ("middleware", "scheduler"),
    [
        ("ROS1", "LRU"),
        ("ROS2", "NPFP"),
        ("ROS2", "PFP"),
        ("ROS2", "ROEDF"),
        ("ROS2", "LOEDF"),
        ("ROS2", "LST"),
    ],
)
def test_estimate_maps_the_quaternion_system_in_ros1_and_with_every_scheduler(
    tmp_path, synthesis_cache, middleware, scheduler
):
    # the small iterative core: the estimate maps the accelerator in minutes, not the fast one
    text = (QUATERNION / "project_iterative.yaml").read_text()
    text = text.replace("middleware: ROS2", f"middleware: {middleware}")
    text = text.replace("scheduler: LRU", f"scheduler: {scheduler}")
    if middleware == "ROS1":
        text = text.replace("distro: humble", "distro: noetic")
    # every module of the example: the accelerator imports its cores, the cores their parts
    sources = {f"{path.stem}__py": path.read_text() for path in QUATERNION.glob("*.py")}
    spec = write_spec(tmp_path, text, **sources)
    out = tmp_path / "build"
    env = {"RFC_CACHE_DIR": str(synthesis_cache)}
    result = run_rfc("build", spec, "-o", out, "--estimate", cwd=ROOT, env=env)
    assert result.returncode == 0, result.stderr
    resources = (out / "report.md").read_text().split("## Resources")[1]
    top = "quaternion_to_euler_iterative_pl"
    total = next(line for line in resources.splitlines() if top in line)
    lut, ff = (int(cell) for cell in total.split("|")[2:4])
    # the CORDIC accelerator alone takes thousands of LUTs; the manager's scheduler is small
    assert 5000 < lut < 30000
    assert 1000 < ff < 10000
