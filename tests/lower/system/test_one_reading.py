"""Generated HDL that every tool reads the same way: GHDL's synthesis of each component is clean.

Constructs that simulators and synthesis tools read differently — a vector compared with a
constant its bits cannot hold, a signal or array element left unassigned on some path (a latch,
or undriven bits), a combinational block that only reads constants (its output keeps its
initial value) — make the RTL, GHDL's netlist and the Verilog disagree. Every component rfc
generates for the examples must synthesize in GHDL without a warning, and its VHDL and Verilog
must hold none of them.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
#: The examples whose logic rfc builds.
EXAMPLES = (
    "quaternion_to_euler/project.yaml",
    "quaternion_to_euler/project_iterative.yaml",  # the small core: iterative CORDICs
    "multi_type/MultiType.yaml",
    "image_pipeline/ImagePipeline.yaml",  # record-first stages, the pixels streamed through
    "rotation_converter/RotationConverterNode.yaml",  # PFP
    "sensor_hub/SensorHub.yaml",  # an HLS core behind its ap_ctrl wrapper
    "franka_fk/franka_fk.yaml",  # interface objects, the arithmetic engine
    "first_accelerator/mirror.yaml",
)

_DECLARED = re.compile(
    r"^\s*(?:signal|variable|constant)?\s*(\w+)\s*:\s*(?:in |out )?\s*"
    r"(?:unsigned|signed|std_logic_vector)\((\d+) downto 0\)",
    re.M | re.I,
)
_COMPARED = re.compile(r"\b(\w+)\s*(>=|<=|/=|>|<|=)\s*(\d+)\b")


def out_of_range_comparisons(vhdl: str) -> list[str]:
    """Comparisons of a declared vector with a natural constant it cannot hold."""
    bits = {m.group(1).lower(): int(m.group(2)) + 1 for m in _DECLARED.finditer(vhdl)}
    bits |= {f"{name}_num": width for name, width in bits.items()}  # MyHDL's port copies
    return [
        line.strip()
        for line in vhdl.splitlines()
        for name, _, value in _COMPARED.findall(line)
        if name.lower() in bits and int(value) >= 2 ** bits[name.lower()]
    ]


def constant_only_blocks(verilog: str) -> list[str]:
    """Verilog always blocks sensitive to nothing but constants: they never run."""
    constants = set(re.findall(r"localparam\s*(?:\[[^\]]*\])?\s*(\w+)", verilog))
    found = []
    for names in re.findall(r"always @\(([^)]*)\)", verilog):
        if all(name.strip() in constants for name in names.split(",")):
            found.append(names)
    return found


@pytest.fixture(scope="module", params=EXAMPLES, ids=lambda spec: spec.removesuffix(".yaml"))
def built(request, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("build")
    result = run_rfc("build", ROOT / "examples" / request.param, "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    return out


def generated_components(out: Path) -> list[str]:
    """The entities rfc generated (MyHDL's package and the structural top level aside)."""
    names = (out / "hw/files.txt").read_text().split()
    return [Path(name).stem for name in names[1:-1]]


def test_every_component_synthesizes_in_ghdl_without_a_warning(built, tmp_path):
    package = built / "hw/pck_myhdl_011.vhd"
    for entity in generated_components(built):
        work = tmp_path / entity
        work.mkdir()
        options = ["--std=08", "-fsynopsys", f"--workdir={work}"]
        source = built / "hw" / f"{entity}.vhd"
        result = subprocess.run(
            ["ghdl", "--synth", *options, package, source, "-e", entity],
            capture_output=True,
            text=True,
            check=False,
        )
        assert result.returncode == 0, f"{entity}: {result.stderr[-2000:]}"
        warnings = [line for line in result.stderr.splitlines() if "warning" in line]
        assert warnings == [], entity


def test_no_vector_is_compared_with_a_constant_outside_its_range(built):
    for entity in generated_components(built):
        vhdl = (built / "hw" / f"{entity}.vhd").read_text()
        assert out_of_range_comparisons(vhdl) == [], entity


def test_no_verilog_block_reads_only_constants(built):
    for path in sorted((built / "hw/verilog").glob("*.v")):
        assert constant_only_blocks(path.read_text()) == [], path.name


def test_the_checks_find_what_they_look_for():
    vhdl = "signal pad: unsigned(2 downto 0);\n  if (pad > 8) then\n  if (pad > 7) then\n"
    assert out_of_range_comparisons(vhdl) == ["if (pad > 8) then"]
    verilog = "localparam [2:0] gap = 3'd4;\nalways @(gap) begin\nalways @(gap, x) begin\n"
    assert constant_only_blocks(verilog) == ["gap"]
