"""Yosys' view of a block: 7-series cells, DSP48E1 register settings and cell-delay timing.

`synth_xilinx -family xc7 -abc9 -flatten` maps rfc's Verilog; `sta` on the mapped netlist, read
back with the 7-series cells' timing models (`cells_sim.v`'s specify blocks), gives the latest
arrival time: the critical path's cell delay, without routing.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

_DSP_REGISTERS = ("AREG", "BREG", "MREG", "PREG")


@dataclass(frozen=True)
class Mapped:
    """A block after `synth_xilinx -abc9`.

    Attributes:
        cells: Cell count by type.
        dsp_registers: Per DSP48E1, its AREG, BREG, MREG and PREG settings.
        arrival_ps: Latest arrival time of `sta`, in picoseconds (cell delays only).
    """

    cells: dict[str, int]
    dsp_registers: tuple[dict[str, int], ...]
    arrival_ps: int

    @property
    def fmax_mhz(self) -> float:
        """The clock the cell delays alone would allow."""
        return 1e6 / self.arrival_ps


def map_xc7(verilog: Path, top: str, workdir: Path) -> Mapped:
    """Map one Verilog file with `synth_xilinx -abc9 -flatten` and run `sta` on the result."""
    netlist, mapped = workdir / f"{top}.json", workdir / f"{top}.mapped.v"
    # `sta` on the mapped netlist read back with the cells' timing (specify) models.
    script = (
        f"read_verilog {verilog}; synth_xilinx -family xc7 -noiopad -abc9 -flatten -top {top}; "
        f"write_json {netlist}; write_verilog -noattr {mapped}; design -reset; "
        f"read_verilog -lib -specify +/xilinx/cells_sim.v; read_verilog {mapped}; "
        f"hierarchy -top {top}; flatten; sta"
    )
    yosys = shutil.which("yosys") or "yosys"
    result = subprocess.run([yosys, "-p", script], capture_output=True, text=True, check=True)
    arrival = re.search(r"Latest arrival time in '\S+' is (\d+)", result.stdout)
    module = json.loads(netlist.read_text())["modules"][top]
    cells: dict[str, int] = {}
    registers = []
    for cell in module["cells"].values():
        cells[cell["type"]] = cells.get(cell["type"], 0) + 1
        if cell["type"] == "DSP48E1":
            registers.append({r: int(cell["parameters"][r], 2) for r in _DSP_REGISTERS})
    return Mapped(cells, tuple(registers), int(arrival.group(1)) if arrival else 0)
