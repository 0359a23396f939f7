"""The hardware lowering: the logic's VHDL and Verilog, Vivado and Vitis HLS scripts, build.sh.

`rfc.lower.system.generate_system` generates the logic into a scratch folder; this lowering
turns its files into artifacts under ``hw/`` (``hw/files.txt`` lists them in compile order)
and ``hw/verilog/`` (the same modules in Verilog, with their own ``files.txt``),
adds the Vivado project values and block design derived from the same netlist
(`rfc.lower.vivado`), one Vitis HLS run per HLS accelerator, and the static ``build.sh``.
`simulation_top` is the top provider of ``rfc sim``: the same logic, generated for GHDL.
"""

from __future__ import annotations

import tempfile
from collections.abc import Iterable
from dataclasses import replace
from importlib import resources
from pathlib import Path

from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.lower.artifacts import Artifact, BuildOptions, ReportSection
from rfc.lower.block_design import block_design, tcl_list, tcl_word
from rfc.lower.system.accelerators import HlsCore
from rfc.lower.system.estimate import estimate_logic, resources_section, timing_section
from rfc.lower.system.generate import SystemHardware, generate_system
from rfc.lower.system.measures import buffers_section, latency_section, verilog_section
from rfc.lower.vivado import VivadoProject, vivado_artifacts
from rfc.toolchain import GhdlError, synthesize_vhdl

#: Where the generated VHDL goes in the build directory.
HW = "hw"
#: Where the same logic goes in Verilog.
VERILOG = f"{HW}/verilog"


def hardware(design: Design, options: BuildOptions) -> Iterable[Artifact | ReportSection]:
    """Every hardware artifact of a design whose logic has anything in it."""
    infrastructure = design.infrastructure
    assert infrastructure is not None
    if not options.hardware or not (infrastructure.subscribers or infrastructure.publishers):
        return
    with tempfile.TemporaryDirectory(prefix="rfc-hw-") as scratch:
        system = generate_system(design, Path(scratch))
        yield from _vhdl(system)
        yield from _verilog(system)
        yield verilog_section(design, system)
        yield latency_section(design, system)
        if system.buffers:
            yield buffers_section(system)
        if options.estimate:
            estimate = estimate_logic(system)
            yield resources_section(system, estimate)
            yield timing_section(design, system, estimate)
    hdl_files = [f"{HW}/{f.name}" for f in system.files]
    project = VivadoProject(
        name=design.project.name,
        part=design.project.fpga_part,
        bus_width=system.bus_width,
        clock_mhz=design.project.clock_mhz,
        multichannel=system.multichannel,
        hdl_files=tuple(hdl_files),
        hls_repos=tuple(f"hls/{core.accelerator}/project/solution/impl/ip" for core in system.hls),
    )
    yield from vivado_artifacts(project, block_design(system.netlist))
    for core in system.hls:
        yield from _hls_run(core, design)
    script = resources.files("rfc.lib").joinpath("scripts/build.sh").read_text()
    yield Artifact("build.sh", "build script (static)", script)


def _vhdl(system: SystemHardware) -> Iterable[Artifact]:
    names = [f.name for f in system.files]
    if len(set(names)) != len(names):
        twice = next(n for n in names if names.count(n) > 1)
        raise RfcError(f"two VHDL files of the logic are both called {twice}",
                       hint="rename one of the accelerator's VHDL sources")  # fmt: skip
    for path in system.files:
        kind = "top-level VHDL" if path.stem == system.top else "VHDL"
        yield Artifact(f"{HW}/{path.name}", kind, path.read_text(encoding="utf-8"))
    yield Artifact(f"{HW}/files.txt", "file list", "\n".join(names) + "\n")


def _verilog(system: SystemHardware) -> Iterable[Artifact]:
    """``hw/verilog/``: the same modules in Verilog, for Yosys and Verilator."""
    names = [f.name for f in system.verilog]
    for path in system.verilog:
        kind = "top-level Verilog" if path.stem == system.top else "Verilog"
        yield Artifact(f"{VERILOG}/{path.name}", kind, path.read_text(encoding="utf-8"))
    yield Artifact(f"{VERILOG}/files.txt", "file list", "\n".join(names) + "\n")


def _hls_run(core: HlsCore, design: Design) -> Iterable[Artifact]:
    folder = f"hls/{core.accelerator}"
    static = resources.files("rfc.lib").joinpath("tcl/hls/run.tcl").read_text()
    yield Artifact(f"{folder}/run.tcl", "HLS tcl (static)", static)
    for source in core.sources:
        yield Artifact(f"{folder}/src/{source.name}", "HLS source (copied)", source.read_text())
    values = [
        ("top", tcl_word(core.top)),
        ("sources", tcl_list([f"src/{s.name}" for s in core.sources])),
        ("cflags", tcl_word("-std=c++14")),
        ("part", tcl_word(design.project.fpga_part)),
        ("clock_ns", f"{1000 / design.project.clock_mhz:g}"),
        ("directives", tcl_list(core.directives)),
    ]
    text = "\n".join(
        [f"# {core.accelerator}: values for run.tcl, generated by rfc. Do not edit."]
        + [f"set hls({key}) {value}" for key, value in values]
    )
    yield Artifact(f"{folder}/values.tcl", "HLS tcl", text + "\n")


def netlist_top(design: Design, directory: Path) -> SystemHardware:
    """The logic of `design` for ``rfc sim --netlist``: what synthesis makes of it.

    Each generated component is replaced by GHDL's synthesized netlist of it; the structural
    top level and VHDL accelerators stay as they are.

    Raises:
        RfcError: The logic holds an HLS core, or GHDL cannot synthesize a component.
    """
    system = simulation_top(design, directory)
    package, *files, top = system.files
    netlists = directory / "netlist"
    netlists.mkdir(exist_ok=True)
    replaced = []
    for path in files:
        if path.parent != directory:  # a VHDL accelerator's own source
            replaced.append(path)
            continue
        try:
            with tempfile.TemporaryDirectory(prefix="rfc-netlist-") as scratch:
                text = synthesize_vhdl([package, path], path.stem, Path(scratch))
        except GhdlError as exc:
            raise RfcError(f"GHDL could not synthesize {path.stem} for --netlist:\n{exc}") from None
        netlist = netlists / path.name
        netlist.write_text(text)
        replaced.append(netlist)
    return replace(system, files=(package, *replaced, top))


def simulation_top(design: Design, directory: Path) -> SystemHardware:
    """The logic of `design` generated into `directory`, for ``rfc sim``.

    Raises:
        RfcError: The logic holds an HLS core, whose VHDL only Vitis HLS makes.
    """
    system = generate_system(design, directory)
    if system.hls:
        names = ", ".join(core.accelerator for core in system.hls)
        raise RfcError(
            f"the logic holds HLS cores ({names}), whose VHDL only Vitis HLS can make: "
            "it cannot be simulated here",
            hint="switch those accelerators to ROS-SW (their reference runs instead) or MyHDL",
        )
    return system
