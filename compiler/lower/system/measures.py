"""The report's figures of the logic: latencies (MyHDL simulation), buffers and Verilog sources.

Targets (docs/architecture.md): a subscriber within ceil(bytes / bus bytes) + 2 cycles, a
publisher within ceil(bytes / bus bytes) + 3, an accelerator within 120; the paper's quaternion
system took 35, 373 and 28 cycles on its 8-bit bus.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from pathlib import Path

from rfc.ir.model import AcceleratorKind, BlockKind, Design
from rfc.lib.devices import bram36
from rfc.lower.artifacts import ReportSection
from rfc.lower.report import markdown_table
from rfc.lower.system.conversion_cache import cached_measurement
from rfc.lower.system.generate import SystemHardware
from rfc.lower.system.latency import (
    gate_latency,
    guard_latency,
    publisher_latency,
    subscriber_latency,
)
from rfc.toolchain import module_instances

#: An accelerator's latency target in cycles (docs/architecture.md, Targets).
ACCELERATOR_TARGET = 120


def latency_section(design: Design, system: SystemHardware) -> ReportSection:
    """Cycles of each converter and MyHDL accelerator on one message, without backpressure."""
    rows = cached_measurement("report latencies", lambda: _latency_rows(design, system))
    lines = [
        "Cycles for one message of default values with every ready high, measured in MyHDL's "
        "simulator: subscriber from the first beat to its fields, accelerator from its inputs to "
        "its outputs, publisher from its fields to the last beat (— where rfc cannot simulate the"
        " block: VHDL and HLS accelerators). Targets: docs/architecture.md (frame size is the "
        "largest frame for variable-size messages). In front of each subscriber, what keeps "
        "malformed frames from its consumers (docs/converters.md, Malformed input): a drop gate "
        "behind a subscriber of fixed-size fields, which adds no cycle, or a frame guard before "
        "one that streams strings or sequences, which holds each frame until a copy of the "
        "subscriber has parsed it: from the frame's first beat in to its first beat out to the "
        "subscriber, the subscriber's own cycles on that frame (its beats, one a cycle, and a few"
        " cycles per string or sequence element) plus a constant; the subscriber's cycles then "
        "follow.",
        "",
        *markdown_table(["block", "name", "cycles", "target"], rows, (False, False, True, True)),
    ]
    return ReportSection("Latencies", tuple(lines))


def _latency_rows(design: Design, system: SystemHardware) -> list[list[object]]:
    """The latency table's rows: each block measured in MyHDL's simulator."""
    infrastructure = design.infrastructure
    assert infrastructure is not None
    rows: list[list[object]] = []
    gate: list[int | None] = []  # measured once: every gate is the same
    for converter in infrastructure.subscribers:
        beats = math.ceil(converter.max_frame_bytes / (converter.bus_width // 8))
        measured = subscriber_latency(converter, system.limits)
        guarded = guard_latency(converter, system.limits)
        if guarded is None:
            gate = gate or [gate_latency()]
            rows.append(["drop gate", f"`{converter.block}`", gate[0], "—"])
        elif measured is None:
            rows.append(["frame guard", f"`{converter.block}`", guarded[1], "—"])
        else:
            cycles = f"{guarded[1]} (subscriber + {guarded[1] - measured})"
            rows.append(["frame guard", f"`{converter.block}`", cycles, "—"])
        rows.append(["subscriber", f"`{converter.block}`", measured, f"≤ {beats + 2}"])
    for block in design.blocks_of(BlockKind.ACCELERATOR):
        hardware = system.accelerators.get(block.accelerator or "")
        if hardware is None:
            continue
        measured = hardware.latency() if hardware.latency else None
        rows.append(["accelerator", f"`{block.name}`", measured, f"≤ {ACCELERATOR_TARGET}"])
    for converter in infrastructure.publishers:
        beats = math.ceil(converter.max_frame_bytes / (converter.bus_width // 8))
        measured = publisher_latency(converter, system.limits)
        rows.append(["publisher", f"`{converter.block}`", measured, f"≤ {beats + 3}"])
    return rows


def buffers_section(system: SystemHardware) -> ReportSection:
    """The publishers' and subscribers' buffers: what they hold and how much block RAM."""
    held = [(block, b, bram36(b.bits, b.words)) for block, bs in system.buffers.items() for b in bs]
    rows: list[list[object]] = [
        [f"`{block}`", f"`{b.path}`", b.words, b.bits, f"{b.size_bits / 8192:.1f}", brams]
        for block, b, brams in held
    ]
    total = sum(brams for _, _, brams in held)
    lines = [
        "A publisher takes a message's strings and sequences only after its other fields (it "
        "needs every length for the frame length), so each gets a FIFO that holds one message "
        "at the project's maxima; behind a MyHDL accelerator (record-first) the message's last "
        "stream goes straight through when it is the last field. A subscriber that hands "
        "strings or sequences on holds each frame whole (`(whole frame)`), or only its bytes "
        "before a last primitive sequence "
        "(`(frame before 'data')`, checked against the size its chunk header declares), until "
        "it is checked, so that a malformed one is dropped before any of it is handed on. "
        f"Together at most {total} block RAMs of 36 Kb "
        "(synthesis may put the small ones in LUT RAM; an xc7z020 has 140); lower the maxima "
        "to shrink them.",
        "",
        *markdown_table(
            ["block", "holds", "words", "bits", "KiB", "BRAM36"],
            rows,
            (False, False, True, True, True, True),
        ),
    ]
    return ReportSection("Buffer memory", tuple(lines))


def verilog_section(design: Design, system: SystemHardware) -> ReportSection:
    """Where each module of ``hw/verilog/`` comes from, and what has no Verilog."""
    rows: list[list[object]] = []
    separate: list[str] = []
    for accelerator in design.accelerators:
        hardware = system.accelerators.get(accelerator.name)
        if hardware is None:
            continue
        if accelerator.kind is AcceleratorKind.VHDL:
            component = hardware.components[0]
            made = "GHDL's synthesized netlist" if component.verilog else "none: stays VHDL"
            rows.append([f"`{accelerator.name}`", "VHDL", made])
        elif accelerator.kind is AcceleratorKind.HLS:
            rows.append([f"`{accelerator.name}`", "HLS", "none: Vitis HLS exports the core"])
        else:
            rows.append([f"`{accelerator.name}`", "MyHDL", "MyHDL's Verilog back-end"])
            separate += _separate_modules(hardware.components[0].verilog)
    lines = [
        "`hw/verilog/` holds the logic in Verilog with the module, port and signal names of "
        "the VHDL: MyHDL's Verilog back-end for the converters, manager, scheduler and "
        "wrappers, rfc's netlist writer for the top level. Accelerators:",
        "",
        *markdown_table(["accelerator", "written in", "Verilog"], rows, (False, False, False)),
    ]
    if separate:
        lines += [
            "",
            "In the Verilog, each rfc.lib arithmetic block of a MyHDL accelerator is a module "
            "of its own, written once per parameter set (the VHDL stays one entity), so that "
            "`--estimate` maps it once: " + ", ".join(separate) + ".",
        ]
    return ReportSection("Verilog", tuple(lines))


def _separate_modules(verilog: Sequence[Path]) -> list[str]:
    """The modules an accelerator's Verilog holds besides its own, with their instances."""
    *modules, own = verilog
    names = [module.stem for module in modules]
    copies = Counter(name for _, name in module_instances(own.read_text(), names))
    return [f"`{name}` x{copies[name]} in `{own.stem}`" for name in names]
