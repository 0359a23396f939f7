"""Resource estimates without vendor tools: Yosys `synth_xilinx` for the 7-series (xc7z020).

`module_resources` maps one module of rfc's own Verilog out of context, cached by the content
of its file (a system's estimate sums its modules, so a rebuild or a sibling system that shares
the accelerator maps only what changed); `estimate_resources` goes through GHDL's synthesis
for designs that exist only in VHDL (a scheduler or converter on its own).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import shutil
import subprocess
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from rfc.toolchain.convert import canonical_lines
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

    def __add__(self, other: Resources) -> Resources:
        """The cells of two designs side by side."""
        return Resources(
            *(
                a + b
                for a, b in zip(dataclasses.astuple(self), dataclasses.astuple(other), strict=True)
            )
        )

    def __mul__(self, copies: int) -> Resources:
        """The cells of `copies` instances of a design."""
        return Resources(*(copies * a for a in dataclasses.astuple(self)))


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


#: Changes whenever the way a module is mapped changes, so old cache entries are not reused.
_FLOW = "synth_xilinx -family xc7 -noiopad, out of context, v1"


def cache_directory() -> Path:
    """Where module figures are kept: ``$RFC_CACHE_DIR/verilog`` or ``~/.cache/rfc/verilog``."""
    root = os.environ.get("RFC_CACHE_DIR") or Path.home() / ".cache" / "rfc"
    return Path(root) / "verilog"


def module_resources(verilog: Path, top: str) -> Resources:
    """Map one Verilog file to the 7-series and count the cells of its module `top`.

    The figures are cached by the file's content, the module and Yosys's version.

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    digest = hashlib.sha256()
    for part in (_FLOW, _yosys_version(), top, *canonical_lines(verilog.read_text())):
        digest.update(part.encode() + b"\n")
    entry = cache_directory() / f"{digest.hexdigest()}.json"
    if entry.is_file():
        return Resources(**json.loads(entry.read_text()))
    with tempfile.TemporaryDirectory(prefix="rfc-synth-") as scratch:
        resources = resources_of_verilog(verilog, top, Path(scratch))
    entry.parent.mkdir(parents=True, exist_ok=True)
    partial = entry.with_suffix(f".{os.getpid()}.tmp")
    partial.write_text(json.dumps(dataclasses.asdict(resources)))
    partial.replace(entry)
    return resources


@cache
def _yosys_version() -> str:
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    result = subprocess.run([executable, "-V"], capture_output=True, text=True, check=False)
    return result.stdout.strip()


def resources_of_verilog(verilog: Path | Sequence[Path], top: str, workdir: Path) -> Resources:
    """Map a Verilog design with `synth_xilinx -family xc7` (no I/O buffers) and count cells."""
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    report = workdir / "stat.json"
    files = [verilog] if isinstance(verilog, Path) else list(verilog)
    script = (
        f"read_verilog {' '.join(str(f) for f in files)}; "
        f"synth_xilinx -family xc7 -noiopad -top {top}; tee -q -o {report} stat -json"
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
