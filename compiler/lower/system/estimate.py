"""`rfc build --estimate`: the logic's cells and critical paths for report.md, without Vivado.

Each module of ``hw/verilog/`` is mapped to the 7-series out of context (Yosys `synth_xilinx
-abc9`, two at a time, cached by content: `rfc.toolchain.module_estimate`); the resources are
summed over the top level's instances, and the whole logic's critical path is the latest of the
modules' own and of the paths across blocks, timed from the modules' boundary logic
(`rfc.toolchain.logic_timing`). An estimated Fmax
below the spec's ``clockMHz`` is a `TimingWarning` naming the path.
"""

from __future__ import annotations

import warnings
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.lower.artifacts import ReportSection
from rfc.lower.report import markdown_table
from rfc.lower.system.generate import SystemHardware
from rfc.toolchain import (
    ModuleEstimate,
    Resources,
    TimingPath,
    estimate_modules,
    logic_timing,
    module_instances,
)
from rfc.toolchain.sta import ROUTING_FACTOR


class TimingWarning(UserWarning):
    """The logic's estimated Fmax is below the clock the spec asks for."""


@dataclass(frozen=True)
class LogicEstimate:
    """The figures of a whole logic.

    Attributes:
        modules: Each module's own figures, by module name.
        copies: How many instances of each module the top level holds.
        timing: The critical path of the whole logic (None when nothing is timed).
    """

    modules: Mapping[str, ModuleEstimate]
    copies: Mapping[str, int]
    timing: TimingPath | None

    @property
    def resources(self) -> Resources:
        """The cells of every instance together."""
        parts = (m.resources * self.copies[name] for name, m in self.modules.items())
        return sum(parts, Resources(0, 0))


def estimate_logic(system: SystemHardware) -> LogicEstimate:
    """Map, count and time every module of a logic, then time the logic as a whole.

    Raises:
        RfcError: The logic holds HLS cores, whose netlists only Vitis HLS makes, or a VHDL
            accelerator GHDL cannot synthesize.
    """
    if system.hls:
        raise RfcError(
            "--estimate needs the whole logic in Verilog, but its HLS cores come from Vitis HLS",
            hint="leave out --estimate; Vitis HLS reports the cores' resources",
        )
    if system.vhdl_only:
        raise RfcError(
            f"--estimate needs the whole logic in Verilog, but GHDL could not synthesize "
            f"{', '.join(system.vhdl_only)}, which stays VHDL",
            hint="run `ghdl --synth --std=08` on the accelerator's sources to see why",
        )
    files = {path.stem: path for path in system.verilog}
    submodules = {name: module_instances(path.read_text(), files) for name, path in files.items()}
    top_level = [(label, entity.name) for label, entity, _ in system.netlist.instances()]
    instances = dict(_instances_below(top_level, submodules))
    copies = Counter(instances.values())
    names = list(copies)
    children = {n: [files[m] for m in dict.fromkeys(m for _, m in submodules[n])] for n in names}
    estimates = estimate_modules([(files[n], n) for n in names], children)
    modules = dict(zip(names, estimates, strict=True))
    by_label = {label: modules[name] for label, name in instances.items()}
    timing = logic_timing(by_label, files[system.top], system.top)
    return LogicEstimate(modules, copies, timing)


def _instances_below(
    instances: list[tuple[str, str]], submodules: Mapping[str, list[tuple[str, str]]]
) -> Iterator[tuple[str, str]]:
    """Every (label, module) of a hierarchy, labels joined by dots (``accelerator.cordic0``).

    An accelerator holds the rfc.lib blocks it repeats as modules of their own
    (`rfc.toolchain.modules`), each mapped once.
    """
    for label, module in instances:
        yield label, module
        below = [(f"{label}.{sub}", name) for sub, name in submodules.get(module, [])]
        yield from _instances_below(below, submodules)


def resources_section(system: SystemHardware, estimate: LogicEstimate) -> ReportSection:
    """LUT/FF/DSP/BRAM of the whole logic, module by module."""
    rows = [
        [_instances(name, estimate.copies[name]), *_cells(module.resources * estimate.copies[name])]
        for name, module in estimate.modules.items()
    ]
    rows.append([f"**{system.top}**", *_cells(estimate.resources)])
    lines = [
        "Yosys `synth_xilinx -family xc7 -noiopad -abc9` on each module of `hw/verilog/` out of "
        "context, summed over the top level's instances (an estimate; Vivado's figures differ).",
        "",
        *markdown_table(
            ["module", "LUT", "FF", "CARRY4", "LUTRAM", "BRAM", "DSP"],
            rows,
            (False, True, True, True, True, True, True),
        ),
    ]
    return ReportSection("Resources", tuple(lines))


def timing_section(
    design: Design, system: SystemHardware, estimate: LogicEstimate
) -> ReportSection:
    """Critical paths of each module and of the whole logic, and the Fmax they allow.

    Warns (`TimingWarning`) when the whole logic's estimate is below the spec's clock.
    """
    clock = design.project.clock_mhz
    rows = [_row(f"`{name}`", m.timing, clock) for name, m in estimate.modules.items()]
    rows.append(_row(f"**{system.top}** (whole logic)", estimate.timing, clock))
    lines = [
        "Yosys `sta` on the same mapping: the cell delay of the latest path, from a register's "
        "clock (or an input) to a register (or an output), with the 7-series cell delays Yosys "
        "ships (Project X-Ray's Artix-7 figures). Routing is not in it: the Fmax assumes it "
        f"takes as long again as the cells (period = {ROUTING_FACTOR:g} x cell delay; "
        "docs/performance.md, Timing). Each module is timed on its own, its ports taken as "
        "registered; the whole logic's path is the latest of theirs and of the paths across "
        "blocks, timed from the modules' boundary logic (the cells between their ports and "
        "first registers), so a path that crosses from one block into another appears only in "
        "its row (in: `a` → `b`).",
        "",
        *markdown_table(
            ["module", "cell delay (ns)", "levels", "Fmax (MHz)", f"{clock:g} MHz", "path", "in"],
            rows,
            (False, True, True, True, False, False, False),
        ),
    ]
    path = estimate.timing
    if path is not None and path.fmax_mhz < clock:
        message = (
            f"the logic's estimated Fmax is {path.fmax_mhz:.0f} MHz, below its clock of "
            f"{clock:g} MHz: critical path {describe(path)}"
        )
        warnings.warn(message, TimingWarning, stacklevel=2)
        lines += ["", f"**Warning**: {message}."]
    return ReportSection("Timing", tuple(lines))


def describe(path: TimingPath) -> str:
    """A path in a sentence: where it runs, its cell delay and its logic levels."""
    where = _blocks(path)
    return (
        f"{path.start or 'an input'} → {path.end or 'an output'} "
        f"({path.delay_ns:.2f} ns of cells over {path.levels} levels"
        + (f", in {where}" if where else "")
        + ")"
    )


def _blocks(path: TimingPath) -> str:
    start, end = path.start_cell, path.end_cell
    if start == end:
        return f"`{start}`" if start else ""
    return f"`{start or 'input'}` → `{end or 'output'}`"


def _row(label: str, path: TimingPath | None, clock: float) -> list[object]:
    if path is None:
        return [label, None, None, None, "yes", "no timed path", None]
    return [
        label,
        f"{path.delay_ns:.2f}",
        path.levels,
        f"{path.fmax_mhz:.0f}",
        "yes" if path.fmax_mhz >= clock else "**no**",
        f"`{path.start or 'input'}` → `{path.end or 'output'}`",
        _blocks(path) or None,
    ]


def _instances(name: str, copies: int) -> str:
    return f"`{name}`" + (f" x{copies}" if copies > 1 else "")


def _cells(cells: Resources) -> list[object]:
    return [cells.lut, cells.ff, cells.carry, cells.lutram, cells.bram, cells.dsp]
