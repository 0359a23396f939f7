"""Resource and timing estimates without vendor tools: Yosys `synth_xilinx` for the 7-series.

`module_estimate` maps one module of rfc's own Verilog out of context with `-abc9` (delay-aware
LUT mapping), counts its cells, times it with `sta` and keeps the mapped netlist, all cached by
the content of its file (a system's estimate sums its modules, so a rebuild or a sibling system
that shares the accelerator maps only what changed); `estimate_modules` runs several at once,
and `system_timing` times the whole logic from the modules' mapped netlists, so that paths
across blocks are seen without mapping anything again. `estimate_resources` and
`estimate_timing` go through GHDL's synthesis for designs that exist only in VHDL (a scheduler
or converter on its own).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import shutil
import subprocess
import tempfile
import threading
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from rfc.toolchain.convert import canonical_lines
from rfc.toolchain.ghdl import synthesize_verilog
from rfc.toolchain.sta import TimingPath, parse_sta, sta_commands

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


#: Changes whenever the way a module is mapped or timed changes, so old cache entries go unused.
_FLOW = "synth_xilinx -family xc7 -noiopad -abc9 -flatten, sta of the mapped netlist, v2"
#: How many modules are mapped at once (the development machines have two cores).
WORKERS = 2
#: The 7-series cell library with its delays (`sta` needs them; `synth_xilinx` keeps none).
_CELLS = "read_verilog -lib -specify +/xilinx/cells_sim.v"


@dataclass(frozen=True)
class ModuleEstimate:
    """One module mapped to the 7-series out of context.

    Attributes:
        resources: Its cells.
        timing: Its critical path, None when nothing in it is timed (a module of wires).
        netlist: Its mapped netlist (Verilog of 7-series cells), for timing a whole system.
    """

    resources: Resources
    timing: TimingPath | None
    netlist: Path


def cache_directory() -> Path:
    """Where module figures are kept: ``$RFC_CACHE_DIR/verilog`` or ``~/.cache/rfc/verilog``."""
    root = os.environ.get("RFC_CACHE_DIR") or Path.home() / ".cache" / "rfc"
    return Path(root) / "verilog"


def module_estimate(verilog: Path, top: str) -> ModuleEstimate:
    """Map one Verilog file to the 7-series with `-abc9`; count and time its module `top`.

    The figures and the mapped netlist are cached by the file's content, the module and
    Yosys's version.

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    digest = hashlib.sha256()
    for part in (_FLOW, _yosys_version(), top, *canonical_lines(verilog.read_text())):
        digest.update(part.encode() + b"\n")
    entry = cache_directory() / f"{digest.hexdigest()}.json"
    netlist = entry.with_suffix(".v")
    if entry.is_file() and netlist.is_file():
        return _read_entry(entry, netlist)
    entry.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="rfc-synth-") as scratch:
        work = Path(scratch)
        mapped = work / f"{top}.mapped.v"
        report = work / "stat.json"
        _run_yosys(
            f"read_verilog {verilog}; synth_xilinx -family xc7 -noiopad -abc9 -flatten "
            f"-top {top}; tee -q -o {report} stat -json; write_verilog -noattr {mapped}; "
            f"design -reset; {_CELLS}; read_verilog {mapped}; hierarchy -top {top}; "
            f"{sta_commands(work / 'sta.log')}",
            str(verilog),
        )
        resources = _resources(report)
        timing = parse_sta((work / "sta.log").read_text())
        _publish(netlist, mapped.read_text())
    value = {"resources": dataclasses.asdict(resources)}
    value["timing"] = None if timing is None else dataclasses.asdict(timing)
    _publish(entry, json.dumps(value))
    return ModuleEstimate(resources, timing, netlist)


def estimate_modules(modules: Sequence[tuple[Path, str]]) -> list[ModuleEstimate]:
    """`module_estimate` of each (file, module), `WORKERS` Yosys processes at a time."""
    with ThreadPoolExecutor(max_workers=WORKERS) as pool:
        return list(pool.map(lambda module: module_estimate(*module), modules))


def system_timing(netlists: Sequence[Path], top_verilog: Path, top: str) -> TimingPath | None:
    """The critical path of a whole logic: its top level over its modules' mapped netlists.

    Paths that cross from one block into another show up here and in no module's own path.
    The result is cached by the content of every file.

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    digest = hashlib.sha256()
    for part in (_FLOW, _yosys_version(), top, *canonical_lines(top_verilog.read_text())):
        digest.update(part.encode() + b"\n")
    for netlist in netlists:
        digest.update(netlist.read_bytes())
    entry = cache_directory() / f"{digest.hexdigest()}.system.json"
    if entry.is_file():
        value = json.loads(entry.read_text())
        return None if value is None else TimingPath(**value)
    with tempfile.TemporaryDirectory(prefix="rfc-sta-") as scratch:
        log = Path(scratch) / "sta.log"
        files = " ".join(str(f) for f in (*netlists, top_verilog))
        _run_yosys(
            f"{_CELLS}; read_verilog {files}; hierarchy -top {top}; {sta_commands(log)}",
            top,
        )
        timing = parse_sta(log.read_text())
    entry.parent.mkdir(parents=True, exist_ok=True)
    _publish(entry, json.dumps(None if timing is None else dataclasses.asdict(timing)))
    return timing


def estimate_timing(files: Sequence[Path], top: str) -> TimingPath | None:
    """Synthesize VHDL (`ghdl --synth`), map it with `-abc9` and time it with `sta`.

    Raises:
        GhdlError: The VHDL does not synthesize.
        RuntimeError: Yosys is missing or fails.
    """
    with tempfile.TemporaryDirectory(prefix="rfc-synth-") as scratch:
        work = Path(scratch)
        verilog = work / f"{top}.v"
        verilog.write_text(synthesize_verilog(files, top, work))
        mapped, log = work / f"{top}.mapped.v", work / "sta.log"
        _run_yosys(
            f"read_verilog {verilog}; synth_xilinx -family xc7 -noiopad -abc9 -flatten "
            f"-top {top}; write_verilog -noattr {mapped}; design -reset; {_CELLS}; "
            f"read_verilog {mapped}; hierarchy -top {top}; {sta_commands(log)}",
            top,
        )
        return parse_sta(log.read_text())


def _read_entry(entry: Path, netlist: Path) -> ModuleEstimate:
    value = json.loads(entry.read_text())
    timing = value["timing"]
    return ModuleEstimate(
        Resources(**value["resources"]),
        None if timing is None else TimingPath(**timing),
        netlist,
    )


def _publish(path: Path, text: str) -> None:
    """Write a cache file whole or not at all (another process may be reading the cache)."""
    partial = path.with_suffix(f"{path.suffix}.{os.getpid()}.{threading.get_ident()}.tmp")
    partial.write_text(text)
    partial.replace(path)


def _run_yosys(script: str, what: str) -> None:
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    result = subprocess.run(
        [executable, "-q", "-p", script], capture_output=True, text=True, check=False
    )
    if result.returncode != 0:
        raise RuntimeError(f"yosys failed on {what}:\n{result.stderr or result.stdout}")


@cache
def _yosys_version() -> str:
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    result = subprocess.run([executable, "-V"], capture_output=True, text=True, check=False)
    return result.stdout.strip()


def resources_of_verilog(verilog: Path | Sequence[Path], top: str, workdir: Path) -> Resources:
    """Map a Verilog design with `synth_xilinx -family xc7` (no I/O buffers) and count cells."""
    report = workdir / "stat.json"
    files = [verilog] if isinstance(verilog, Path) else list(verilog)
    script = (
        f"read_verilog {' '.join(str(f) for f in files)}; "
        f"synth_xilinx -family xc7 -noiopad -top {top}; tee -q -o {report} stat -json"
    )
    _run_yosys(script, str(verilog))
    return _resources(report)


def _resources(report: Path) -> Resources:
    """The cells of Yosys' `stat -json` report."""
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
