"""Resource estimates without vendor tools: Yosys `synth_xilinx` for the 7-series (xc7z020)."""

from __future__ import annotations

import json
import shutil
import subprocess
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rfc.toolchain.ghdl import synthesize_verilog

_LUTS = ("LUT1", "LUT2", "LUT3", "LUT4", "LUT5", "LUT6")
_FFS = ("FDRE", "FDSE", "FDCE", "FDPE", "FDR", "FDS", "FDC", "FDP", "FD")
_LUTRAM = ("RAM32X1D", "RAM64X1D", "RAM128X1D", "RAM32M", "RAM64M", "SRL16E", "SRLC32E")


@dataclass(frozen=True)
class Resources:
    """Cells of a design mapped to the Xilinx 7-series by Yosys.

    Attributes:
        lut: LUT1 to LUT6 cells.
        ff: Flip-flops of every flavour.
        carry: CARRY4 cells.
        lutram: Distributed RAM and shift-register cells (LUTs used as memory).
        bram: Block RAM tiles (RAMB18/RAMB36).
        dsp: DSP48E1 slices.
    """

    lut: int
    ff: int
    carry: int = 0
    lutram: int = 0
    bram: int = 0
    dsp: int = 0


def estimate_resources(files: Sequence[Path], top: str) -> Resources:
    """Synthesize VHDL (`ghdl --synth`) then map it with Yosys and count the cells.

    Raises:
        GhdlError: The VHDL does not synthesize.
        RuntimeError: Yosys is missing or fails.
    """
    with tempfile.TemporaryDirectory(prefix="rfc-synth-") as scratch:
        work = Path(scratch)
        verilog = work / f"{top}.v"
        verilog.write_text(synthesize_verilog(files, top, work))
        return resources_of_verilog(verilog, top, work)


def resources_of_verilog(verilog: Path, top: str, workdir: Path) -> Resources:
    """Map a Verilog design with `synth_xilinx -family xc7` (no I/O buffers) and count cells."""
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    report = workdir / "stat.json"
    script = (
        f"read_verilog {verilog}; synth_xilinx -family xc7 -noiopad -top {top}; "
        f"tee -q -o {report} stat -json"
    )
    result = subprocess.run(
        [executable, "-q", "-p", script], capture_output=True, text=True, check=False
    )
    if result.returncode != 0:
        raise RuntimeError(f"yosys failed on {verilog}:\n{result.stderr or result.stdout}")
    cells = json.loads(report.read_text())["design"]["num_cells_by_type"]
    count = lambda names: sum(cells.get(n, 0) for n in names)  # noqa: E731
    return Resources(
        lut=count(_LUTS),
        ff=count(_FFS),
        carry=cells.get("CARRY4", 0),
        lutram=count(_LUTRAM),
        bram=count(("RAMB18E1", "RAMB36E1")),
        dsp=cells.get("DSP48E1", 0),
    )
