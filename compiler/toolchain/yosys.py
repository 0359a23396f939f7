"""Resource and timing estimates without vendor tools: Yosys `synth_xilinx` for the 7-series.

The scripts rfc runs and how: `map_module` maps one module of rfc's own Verilog out of context
with `-abc9` (delay-aware LUT mapping), counts its cells, times it with `sta` and keeps its
boundary logic (the mapped cells between its ports and its first registers), reading only the
cell libraries the module needs; `flattened_timing` times mapped modules together.
`rfc.toolchain.module_estimates` caches the first and times a whole logic with the second.
`estimate_resources` and `estimate_timing` go through GHDL's synthesis for designs that exist
only in VHDL (a scheduler or converter on its own).
"""

from __future__ import annotations

import dataclasses
import json
import shutil
import subprocess
import tempfile
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from rfc.toolchain.ghdl import synthesize_verilog
from rfc.toolchain.sta import TimingPath, parse_sta

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
    with _synthesized(files, top) as verilog:
        return resources_of_verilog(verilog, top, verilog.parent)


@contextmanager
def _synthesized(files: Sequence[Path], top: str) -> Iterator[Path]:
    """The Verilog GHDL synthesizes from VHDL `files`, in a scratch folder kept while in use."""
    with tempfile.TemporaryDirectory(prefix="rfc-synth-") as scratch:
        verilog = Path(scratch) / f"{top}.v"
        verilog.write_text(synthesize_verilog(files, top, verilog.parent))
        yield verilog


#: The 7-series cell library with its delays (`sta` needs them; `synth_xilinx` keeps none).
_CELLS = "read_verilog -lib -specify +/xilinx/cells_sim.v"
#: The rest of the 7-series primitives (clock managers, transceivers, I/O serializers, …) as
#: black boxes: `synth_xilinx` reads them first thing, after `_CELLS`.
_OTHER_CELLS = "read_verilog -lib +/xilinx/cells_xtra.v"
#: `synth_xilinx`'s step `map_memory` for the 7-series, as Yosys writes it (0.23 to 2026) but
#: for its last command, the mapping of block RAMs (`_Libraries`).
_MEMORY_LIBMAP = (
    "memory_libmap -logic-cost-rom 0.015625 -lib +/xilinx/lutrams_xc5v.txt "
    "-lib +/xilinx/brams_xc4v.txt -D HAS_SIZE_36 -D HAS_CASCADE -D HAS_CONFLICT_BUG "
    "-D HAS_MIXWIDTH_SDP"
)
_LUTRAM_MAP = "techmap -map +/xilinx/lutrams_xc5v_map.v"
#: The cells `memory_libmap` leaves for the block-RAM mapping to turn into RAMB18E1/RAMB36E1.
_BLOCK_RAMS = "t:$__XILINX_BLOCKRAM_*"
#: Cells that hold state: a path starts at their clock and ends at their inputs.
_REGISTERS = "t:FD* t:DSP48E1 t:RAMB* t:SRL* t:RAM*"
#: Flip-flops, whose data and control pins end a path and whose output starts one.
_FLIP_FLOPS = "FDRE,FDSE,FDCE,FDPE"
#: The cells between a module's ports and its first registers, the clock buffers with them: the
#: input cone of every output back to the flip-flops that launch it, and the output cone of
#: every input up to the flip-flops that capture it (through DSP and RAM cells, cautiously).
_BOUNDARY = (
    f"o:* %ci*:-{_FLIP_FLOPS}[D,CE,R,S,CLR,PRE] i:* %co*:-{_FLIP_FLOPS}[Q]:-BUFG %u t:BUFG %u"
)


def _boundary(submodules: Sequence[str]) -> str:
    """`_BOUNDARY`, and the same cones at the ports of the instances of `submodules`.

    A module that instantiates others (mapped on their own, black boxes here) has paths that
    cross into them: the cells between its registers and their ports are boundary logic too,
    and the instances stay in it, so that flattening the boundary netlists joins the paths.
    """
    cones = [_BOUNDARY]
    for name in submodules:
        cones.append(
            f"t:{name} %ci*:-{_FLIP_FLOPS}[D,CE,R,S,CLR,PRE] %u "
            f"t:{name} %co*:-{_FLIP_FLOPS}[Q]:-BUFG %u"
        )
    return " ".join(cones)


@dataclass(frozen=True)
class Module:
    """A module to map: its file, its name, the files of the modules it instantiates."""

    verilog: Path
    top: str
    submodules: tuple[Path, ...] = ()

    def read(self) -> str:
        """The Yosys commands that read it, its submodules as black boxes."""
        return f"{self.black_boxes()}read_verilog {self.verilog}"

    def black_boxes(self) -> str:
        """The Yosys commands that read its submodules' ports (as black boxes)."""
        return "".join(f"read_verilog -lib {f}; " for f in self.submodules)


def map_module(module: Module, work: Path) -> tuple[Resources, TimingPath | None, Path]:
    """Map, count and time `module` in the folder `work`.

    Returns its cells, its critical path and the file of its boundary logic; a module with a
    block RAM is mapped twice more (Yosys 0.23's abc9 aborts on block RAMs).

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    report = work / _STAT
    try:
        _run_mapping(
            lambda libs: _estimate_script(module, work, libs), str(module.verilog), block_ram=False
        )
    except _BlockRamMapMissingError:
        # Yosys 0.23's abc9 aborts on every block RAM (a mapping with it would fail after
        # minutes): count with the plain mapping, time with the memories in distributed RAM
        # (docs/performance.md, "Timing").
        _run_mapping(
            lambda libs: (
                f"{_mapping(module, libraries=libs, abc9=False)}; tee -q -o {report} stat -json"
            ),
            str(module.verilog),
            start=_Libraries(block_ram=True),
        )
        _run_mapping(
            lambda libs: (
                f"{_mapping(module, '-nobram', libraries=libs)}; "
                f"{_timing_and_boundary(module, work)}"
            ),
            str(module.verilog),
        )
    return _resources(report), parse_sta((work / _STA).read_text()), work / _BOUNDARY_LOGIC


def flattened_timing(files: Sequence[Path], top: str) -> TimingPath | None:
    """`sta` of module `top` over mapped Verilog `files`, flattened: its critical path.

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    with tempfile.TemporaryDirectory(prefix="rfc-sta-") as scratch:
        log = Path(scratch) / "sta.log"
        _run_yosys(
            f"{_CELLS}; read_verilog {' '.join(map(str, files))}; hierarchy -top {top}; "
            f"flatten; rename -wire {_REGISTERS}; tee -q -o {log} sta",
            top,
        )
        return parse_sta(log.read_text())


#: What `estimate_script` writes in its folder: cell counts, `sta`'s report, boundary logic.
_STAT, _STA, _BOUNDARY_LOGIC = "stat.json", "sta.log", "boundary.v"


def estimate_script(verilog: Path, top: str, work: Path, submodules: Sequence[Path] = ()) -> str:
    """The Yosys script `module_estimate` runs on module `top` of `verilog` (no block RAM).

    It writes into `work` the cell counts (``stat.json``), `sta`'s report (``sta.log``) and
    the boundary logic (``boundary.v``). tools/profile_estimate.py runs it with ``yosys -d``
    to see where a module's mapping spends its time.
    """
    return _estimate_script(Module(verilog, top, tuple(submodules)), work)


@dataclass(frozen=True)
class _Libraries:
    """Which of `synth_xilinx`'s libraries a mapping reads; `_run_mapping` adds what it lacks.

    Most generated modules need neither: `cells_xtra.v` holds primitives no generated logic
    instantiates, and reading the block-RAM mapping (`brams_xc6v_map.v`) costs 1.2 to 1.7 s of
    CPU a module, though few modules have a memory large enough for a block RAM.
    """

    other_cells: bool = False
    block_ram: bool = False

    def cells(self) -> str:
        """The commands reading the cell library: with the other primitives, or not."""
        return f"{_CELLS}; {_OTHER_CELLS}" if self.other_cells else _CELLS


#: What a mapping reads first: the 7-series cells, no block-RAM mapping.
_FEWEST_LIBRARIES = _Libraries()


def _estimate_script(module: Module, work: Path, libraries: _Libraries = _FEWEST_LIBRARIES) -> str:
    return (
        f"{_mapping(module, libraries=libraries)}; tee -q -o {work / _STAT} stat -json; "
        f"{_timing_and_boundary(module, work)}"
    )


def _mapping(
    module: Module, options: str = "", libraries: _Libraries = _FEWEST_LIBRARIES, abc9: bool = True
) -> str:
    """Read `module` and map it to the 7-series, flattened (with `-abc9` unless told otherwise)."""
    flow = " ".join(filter(None, ("-abc9" if abc9 else "", "-flatten", options)))
    return f"{module.read()}; {_synth_xilinx(module.top, flow, libraries)}"


def _synth_xilinx(top: str, options: str, libraries: _Libraries) -> str:
    """`synth_xilinx -family xc7 -noiopad` with `options`, reading only `libraries`.

    rfc runs the script's first step (`begin`: read the cell libraries, set the top module)
    itself. Without `libraries.block_ram` it runs `map_memory` itself too, but for the mapping
    of block RAMs, and asserts that there is none to map (`_BlockRamMapMissingError`).
    """
    synth = " ".join(filter(None, ("synth_xilinx -family xc7 -noiopad", options, f"-top {top}")))
    begin = f"{libraries.cells()}; hierarchy -check -top {top}"
    if libraries.block_ram:
        return f"{begin}; {synth} -run prepare:"
    limits = "-no-auto-block -no-auto-huge" if "-nobram" in options.split() else "-no-auto-huge"
    return (
        f"{begin}; {synth} -run prepare:map_memory; {_MEMORY_LIBMAP} {limits}; {_LUTRAM_MAP}; "
        f"select -assert-none {_BLOCK_RAMS}; {synth} -run map_ffram:"
    )


def _timing_and_boundary(module: Module, work: Path) -> str:
    """Time the mapped `module` into ``work/sta.log``; keep its boundary logic in ``boundary.v``."""
    submodules = [f.stem for f in module.submodules]
    # the timing deleted the black boxes: their ports' directions steer the cones again
    return (
        f"{_timing_commands(module.top, work / _STA, submodules)}; {module.black_boxes()}"
        f"select -set boundary {_boundary(submodules)}; setattr -set keep 1 @boundary; "
        f"delete c:* @boundary %d; opt_clean; write_verilog -noattr {work / _BOUNDARY_LOGIC}"
    )


def estimate_timing(files: Sequence[Path], top: str) -> TimingPath | None:
    """Synthesize VHDL (`ghdl --synth`), map it with `-abc9` and time it with `sta`.

    Raises:
        GhdlError: The VHDL does not synthesize.
        RuntimeError: Yosys is missing or fails.
    """
    with _synthesized(files, top) as verilog:
        log = verilog.parent / "sta.log"
        module = Module(verilog, top)
        _run_mapping(
            lambda libs: f"{_mapping(module, libraries=libs)}; {_timing_commands(top, log)}", top
        )
        return parse_sta(log.read_text())


def _timing_commands(top: str, log: Path, black_boxes: Sequence[str] = ()) -> str:
    """Time the netlist `synth_xilinx` just mapped, writing `sta`'s report to `log`.

    `synth_xilinx` leaves the cell library without the delays of carries and wide muxes, so
    `sta` would count them as free: the library is read again with its `specify` blocks (in
    place, rather than writing the netlist out and reading it back: for the largest modules
    that took minutes). Registers are named after the signals they drive, so that a path names
    registers rather than ``$abc$123``. The instances of `black_boxes` (submodules mapped on
    their own) are left out of the timing only: a path into or out of one crosses into
    another module, which `crossing_timing` times whole.
    """
    sta = f"tee -q -o {log} sta"
    if black_boxes:
        instances = " ".join(f"t:{name}" for name in black_boxes)
        sta = f"design -save mapped; delete {instances}; {sta}; design -load mapped"
    return (
        f"delete =A:blackbox =A:whitebox; {_CELLS}; hierarchy -top {top}; "
        f"rename -wire {_REGISTERS}; {sta}"
    )


def _run_mapping(
    script: Callable[[_Libraries], str],
    what: str,
    start: _Libraries = _FEWEST_LIBRARIES,
    block_ram: bool = True,
) -> None:
    """Run a mapping `script` with the `start` libraries, then with those it turns out to need.

    `synth_xilinx` reads 1.4 MB of other primitives' black boxes (`_OTHER_CELLS`) that no
    generated logic instantiates, and carries them through every pass: 2 to 4 s of CPU per
    module. The mapping is the same but for the order ABC meets the cells in (Yosys numbers
    fewer of them first), which moves a large module's LUT count by a fraction of a percent
    at most. A design that instantiates one of those primitives is mapped again with them; one
    with a memory for a block RAM, again with the block-RAM mapping (unless not `block_ram`:
    then `_BlockRamMapMissingError` says it has one).
    """
    libraries = start
    while True:
        try:
            _run_yosys(script(libraries), what)
            return
        except _MissingModuleError:
            if libraries.other_cells:
                raise
            libraries = dataclasses.replace(libraries, other_cells=True)
        except _BlockRamMapMissingError:
            if libraries.block_ram or not block_ram:
                raise
            libraries = dataclasses.replace(libraries, block_ram=True)


def _run_yosys(script: str, what: str) -> None:
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    result = subprocess.run(
        [executable, "-q", "-p", script], capture_output=True, text=True, check=False
    )
    if result.returncode != 0:
        message = f"yosys failed on {what}:\n{result.stderr or result.stdout}"
        if "is not part of the design" in result.stderr:
            raise _MissingModuleError(message)
        if "Assertion failed" in result.stderr and _BLOCK_RAMS in result.stderr:
            raise _BlockRamMapMissingError(message)
        raise RuntimeError(message)


class _MissingModuleError(RuntimeError):
    """The design instantiates a module Yosys was not given (`hierarchy -check`)."""


class _BlockRamMapMissingError(RuntimeError):
    """`memory_libmap` chose a block RAM: the mapping must read `brams_xc6v_map.v` after all."""


@cache
def yosys_version() -> str:
    """`yosys -V`: part of every cached figure's key."""
    executable = shutil.which("yosys")
    if executable is None:
        raise RuntimeError("yosys is not installed; run tools/setup.sh")
    result = subprocess.run([executable, "-V"], capture_output=True, text=True, check=False)
    return result.stdout.strip()


def resources_of_verilog(verilog: Path | Sequence[Path], top: str, workdir: Path) -> Resources:
    """Map a Verilog design with `synth_xilinx -family xc7` (no I/O buffers) and count cells."""
    report = workdir / "stat.json"
    files = [verilog] if isinstance(verilog, Path) else list(verilog)
    read = f"read_verilog {' '.join(str(f) for f in files)}"
    _run_mapping(
        lambda libs: f"{read}; {_synth_xilinx(top, '', libs)}; tee -q -o {report} stat -json",
        str(verilog),
    )
    return _resources(report)


def _resources(report: Path) -> Resources:
    """The cells of Yosys' `stat -json` report."""
    cells: dict[str, int] = json.loads(report.read_text())["design"]["num_cells_by_type"]

    def count(names: Sequence[str]) -> int:
        return sum(cells.get(name, 0) for name in names)

    return Resources(
        lut=count(_LUTS),
        ff=count(_FFS),
        carry=cells.get("CARRY4", 0),
        lutram=count(_LUTRAM),
        bram=count(("RAMB18E1", "RAMB36E1")),
        dsp=cells.get("DSP48E1", 0),
    )
