"""GHDL: analysis and elaboration checks, and synthesis of VHDL to Verilog for Yosys."""

from __future__ import annotations

import shutil
import subprocess
from collections.abc import Sequence
from pathlib import Path

#: VHDL standard rfc generates and checks against.
STANDARD = "08"


class GhdlError(RuntimeError):
    """GHDL rejected generated VHDL: a bug in the generator, reported with GHDL's own words."""


def _ghdl(args: Sequence[str], workdir: Path) -> str:
    executable = shutil.which("ghdl")
    if executable is None:
        raise GhdlError("ghdl is not installed; run tools/setup.sh")
    workdir.mkdir(parents=True, exist_ok=True)
    result = subprocess.run(
        [executable, *args], cwd=workdir, capture_output=True, text=True, check=False
    )
    if result.returncode != 0:
        raise GhdlError(f"ghdl {' '.join(args[:1])} failed:\n{result.stderr or result.stdout}")
    return result.stdout


def _vhdl(files: Sequence[Path]) -> list[Path]:
    return [Path(f).resolve() for f in files if Path(f).suffix in (".vhd", ".vhdl")]


def analyze(files: Sequence[Path], workdir: Path, top: str | None = None) -> None:
    """Analyze VHDL files in order (and elaborate `top` when given).

    Raises:
        GhdlError: A file does not analyze or the design does not elaborate.
    """
    options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={workdir}"]
    _ghdl(["-a", *options, *map(str, _vhdl(files))], workdir)
    if top:
        _ghdl(["-e", *options, top], workdir)


def synthesize_verilog(files: Sequence[Path], top: str, workdir: Path) -> str:
    """Synthesize a VHDL design with `ghdl --synth` and return it as Verilog text.

    Raises:
        GhdlError: GHDL cannot synthesize the design.
    """
    options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={workdir}"]
    return _ghdl(
        ["--synth", *options, "--out=verilog", *map(str, _vhdl(files)), "-e", top], workdir
    )
