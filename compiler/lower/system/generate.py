"""Assemble the whole logic of a design: components, cells, wiring, top-level VHDL.

The manager sits between the DMA's two streams and the converters (subscriber ``i`` on its
``sub<i>`` group, publisher ``j`` — scheduler input ``j`` — on ``pub<j>``); the model's
hardware connections join converters and accelerators through `rfc.lower.system.top`; a
message that feeds several blocks goes through a handshake fork.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rfc.errors import located
from rfc.ir.infrastructure import Converter, Scheduler
from rfc.ir.model import BlockKind, Connection, Design, Endpoint
from rfc.lib.converters.buffers import Buffer
from rfc.lib.converters.malformed import DROP_REASONS, status_port
from rfc.lib.converters.plan import accelerator_ports
from rfc.lib.converters.ports import COUNTER_BITS, Direction, Side
from rfc.lib.manager.entity import ManagerShape
from rfc.lib.schedulers.spec import DEFAULT_IDLE, AnySchedulerSpec, SchedulerSpec
from rfc.lower.netlist import EntityDecl, Netlist, PortDecl, constant
from rfc.lower.system.accelerators import AcceleratorHardware, HlsCore, accelerator_hardware
from rfc.lower.system.busy import busy_port, watch_blocks, watched_blocks
from rfc.lower.system.components import (
    Component,
    converter_component,
    fork_component,
    manager_component,
)
from rfc.lower.system.guards import SubscriberGuards
from rfc.lower.system.interfaces import MANAGER, MESSAGE
from rfc.lower.system.myhdl_top import missing_blocks, myhdl_logic
from rfc.lower.system.slices import RegisterSlices
from rfc.lower.system.stream_marks import StreamMarks
from rfc.lower.system.top import CLOCK, RESET_N, Interface, Terminal, TopBuilder, wire_connection
from rfc.messages.limits import Limits
from rfc.passes.check_hardware import check_buffer_memory, converter_location, record_first
from rfc.passes.names import snake_identifier as identifier
from rfc.passes.resolve_scheduler import ResolveScheduler

#: The DMA-side stream groups of the top level (docs/protocol.md).
MM2S, S2MM = "s_axis_mm2s", "m_axis_s2mm"
_STREAM = ("tdata", "tkeep", "tvalid", "tready", "tlast")


@dataclass(frozen=True)
class SystemHardware:
    """The generated logic.

    Attributes:
        top: The top-level entity.
        netlist: Its wiring.
        files: Every VHDL file, in compile order, the top level last.
        verilog: Every Verilog file, in compile order, the top level last.
        vhdl_only: The entities that have no Verilog (VHDL accelerators GHDL cannot
            synthesize, vendor cores).
        ghdl_verilog: The entities whose Verilog is GHDL's netlist (VHDL accelerators).
        bus_width: Bits of the DMA streams.
        hls: The HLS cores it instantiates (their VHDL comes from Vitis HLS, not from rfc).
        multichannel: Whether the DMA must be multichannel (the scheduler preempts).
        accelerators: The hardware of each accelerator type in the logic, by type name.
        limits: The maxima of strings and sequences the converters were built for.
        buffers: The FIFOs in front of each publisher that takes strings or sequences, by block.
        busy: The blocks the top level's ``busy`` bits watch, bit 0 first
            (`rfc.lower.system.busy`).
        blocks: The MyHDL block of each entity that has one, by entity name.
    """

    top: str
    netlist: Netlist
    files: tuple[Path, ...]
    verilog: tuple[Path, ...]
    vhdl_only: tuple[str, ...]
    ghdl_verilog: tuple[str, ...]
    bus_width: int
    hls: tuple[HlsCore, ...]
    multichannel: bool
    accelerators: Mapping[str, AcceleratorHardware]
    limits: Limits
    buffers: Mapping[str, tuple[Buffer, ...]]
    busy: tuple[str, ...] = ()
    blocks: Mapping[str, Callable[..., Any]] = field(default_factory=dict, compare=False)

    @property
    def sources(self) -> list[Path]:
        """The VHDL in compile order (the simulator's view)."""
        return list(self.files)

    @property
    def without_myhdl(self) -> list[str]:
        """The entities with no MyHDL block (VHDL accelerators, vendor cores)."""
        return missing_blocks(self.netlist, self.blocks)

    @property
    def myhdl(self) -> Callable[..., Any] | None:
        """The whole logic as a MyHDL block factory (port signals by name), if it has one."""
        return None if self.without_myhdl else myhdl_logic(self.netlist, self.blocks)


def top_name(design: Design) -> str:
    """The top-level entity of a design's logic."""
    return f"{identifier(design.project.name)}_pl"


def scheduler_spec(scheduler: Scheduler) -> AnySchedulerSpec | None:
    """The hardware scheduler of the publishers (None without publishers).

    Each input's transfer time is its publisher's transfer in beats; its deadline the spec's,
    else implicit (transfer plus `DEFAULT_IDLE`).
    """
    if not scheduler.inputs:
        return None
    transfer = [i.transfer_beats for i in scheduler.inputs]
    deadline = [
        i.deadline or i.period or t + DEFAULT_IDLE
        for i, t in zip(scheduler.inputs, transfer, strict=True)
    ]
    return SchedulerSpec.create(scheduler.algorithm, len(transfer), transfer, deadline)


def generate_system(
    design: Design, directory: Path, limits: Limits | None = None
) -> SystemHardware:
    """Generate the logic of `design` into `directory`.

    Raises:
        RfcError: Something in the design cannot become hardware (an accelerator off the port
            convention, an unsupported message shape or fan-out).
    """
    if design.infrastructure and design.infrastructure.scheduler.algorithm == "auto":
        design = ResolveScheduler().apply(design)  # rfc sim compiles without the build passes
    infrastructure = design.infrastructure
    assert infrastructure is not None, "lower a design after derive-infrastructure"
    limits = limits or design.project.maxima
    width = design.project.bus_width
    directory.mkdir(parents=True, exist_ok=True)
    builder = TopBuilder(_top_entity(design), f"{top_name(design)}: the programmable logic of "
                         f"{design.project.name}, generated by rfc. Do not edit.")  # fmt: skip
    components: list[Component] = []
    interfaces: dict[tuple[str, str], Interface] = {}
    buffers: dict[str, tuple[Buffer, ...]] = {}

    spec = scheduler_spec(infrastructure.scheduler)
    shape = ManagerShape(
        width, len(infrastructure.subscribers), len(infrastructure.publishers), spec
    )
    manager = manager_component(shape, directory, f"{identifier(design.project.name)}_manager")
    components.append(manager)
    builder.cell(MANAGER, manager.entity)
    for signal in _STREAM:
        builder.connect(
            Terminal(MANAGER, f"{S2MM}_{signal}"), builder.netlist.port(f"{S2MM}_{signal}")
        )

    guards = SubscriberGuards(identifier(design.project.name), width, directory, limits)
    record_first_publishers: set[str] = set()
    for side, converters in (
        (Side.SUBSCRIBER, infrastructure.subscribers),
        (Side.PUBLISHER, infrastructure.publishers),
    ):
        for converter in converters:
            label = identifier(converter.block)
            streamed_through = side is Side.PUBLISHER and record_first(design, converter)
            if streamed_through:
                record_first_publishers.add(converter.block)
            where = converter_location(design, converter)
            with located(where):
                component = converter_component(
                    converter, side, directory, f"{label}_{side.value}", limits, streamed_through
                )
                pins = accelerator_ports(converter.layout, width, side, limits)
            components.append(component)
            if component.buffers:
                buffers[converter.block] = component.buffers
            builder.cell(label, component.entity)
            interface = {p.name: Terminal(label, p.name) for p in pins}
            if side is Side.PUBLISHER:
                _wire_dma(builder, label, converter, side)
                interfaces[(converter.block, "in0")] = interface
                continue
            with located(where):
                interfaces[(converter.block, "out0")] = guards.protect(
                    builder, label, converter, interface, _wire_dma
                )
    guards.dma_input(builder, Terminal(MANAGER, MM2S))  # through a header tap if a guard needs it
    components += guards.components
    buffers |= guards.buffers

    hardware_types: dict[str, AcceleratorHardware] = {}
    for block in design.blocks_of(BlockKind.ACCELERATOR):
        if block.name in infrastructure.software:
            continue
        accelerator = design.accelerator(block.accelerator or "")
        if accelerator.name not in hardware_types:
            with located(accelerator.location):
                hardware = accelerator_hardware(accelerator, block, width, limits, directory)
            hardware_types[accelerator.name] = hardware
            components += hardware.components
        hardware = hardware_types[accelerator.name]
        label = identifier(block.name)
        cells = {suffix: f"{label}_{suffix}" if suffix else label for suffix, _ in hardware.cells}
        for suffix, entity in hardware.cells:
            builder.cell(cells[suffix], entity)
        for source, output, target, input_ in hardware.wires:
            builder.wire(Terminal(cells[source], output), Terminal(cells[target], input_))
        for (port, role), (suffix, name) in hardware.pins.items():
            terminals = interfaces.setdefault((block.name, port), {})
            interfaces[(block.name, port)] = {**terminals, role: Terminal(cells[suffix], name)}

    check_buffer_memory(design, buffers)  # after the accelerators: their errors come first
    slices = RegisterSlices(identifier(design.project.name), directory)
    forks: dict[int, Component] = {}
    marks = StreamMarks(identifier(design.project.name), width, directory, limits)
    by_source: dict[tuple[str, str], list[Connection]] = defaultdict(list)
    for connection in infrastructure.hardware_connections:
        by_source[(connection.source.block, connection.source.port or "")].append(connection)
    for origin, connections in by_source.items():
        targets = [interfaces[(c.destination.block, c.destination.port or "")] for c in connections]
        what = f"connection {connections[0].source} → {connections[0].destination}"
        with located(connections[0].location):
            if len(targets) == 1:
                complete = marks.complete(
                    builder, design, connections[0], interfaces[origin], targets[0]
                )
                into = connections[0].destination
                sliced = slices.insert(
                    builder,
                    targets[0],
                    _slice_label(into),
                    streams=into.block not in record_first_publishers,
                )
                wire_connection(builder, complete, sliced, what)
                continue
            if len(targets) not in forks:
                forks[len(targets)] = fork_component(
                    len(targets), directory, f"rfc_fork{len(targets)}"
                )
                components.append(forks[len(targets)])
            sliced_targets = [
                slices.insert(builder, target, _slice_label(c.destination))
                for c, target in zip(connections, targets, strict=True)
            ]
            fork = forks[len(targets)].entity
            _fan_out(builder, interfaces[origin], sliced_targets, fork, what)

    components += marks.components
    components += slices.components
    _tie_unused_readies(builder)
    components += watch_blocks(builder, design, interfaces, directory)
    netlist = builder.finish()
    top_file = directory / f"{top_name(design)}.vhd"
    top_file.write_text(netlist.render())
    top_verilog = directory / f"{top_name(design)}.v"
    top_verilog.write_text(netlist.render_verilog())
    files = list(dict.fromkeys(f for component in components for f in component.files))
    files.sort(key=lambda f: not f.name.startswith("pck_myhdl"))  # MyHDL's package first
    verilog = list(dict.fromkeys(f for component in components for f in component.verilog))
    vendor = [e.name for _, e in builder.cells() if e.vlnv]
    return SystemHardware(
        top=top_name(design),
        netlist=netlist,
        files=(*files, top_file),
        verilog=(*verilog, top_verilog),
        vhdl_only=(*(c.entity.name for c in components if not c.verilog), *vendor),
        ghdl_verilog=tuple(c.entity.name for c in components if c.verilog_by_ghdl),
        bus_width=width,
        hls=tuple(h.hls for h in hardware_types.values() if h.hls is not None),
        multichannel=spec is not None and _preemptive(spec),
        accelerators=hardware_types,
        limits=limits,
        buffers=buffers,
        busy=watched_blocks(design),
        blocks={c.entity.name: c.myhdl for c in components if c.myhdl is not None},
    )


def _top_entity(design: Design) -> EntityDecl:
    width = design.project.bus_width
    ports = [PortDecl(CLOCK, Direction.IN, 1, True), PortDecl(RESET_N, Direction.IN, 1, True)]
    for group, into in ((MM2S, True), (S2MM, False)):
        data, back = (Direction.IN, Direction.OUT) if into else (Direction.OUT, Direction.IN)
        ports += [
            PortDecl(f"{group}_tdata", data, width),
            PortDecl(f"{group}_tkeep", data, width // 8),
            PortDecl(f"{group}_tvalid", data, 1, True),
            PortDecl(f"{group}_tready", back, 1, True),
            PortDecl(f"{group}_tlast", data, 1, True),
        ]
    assert design.infrastructure is not None
    for converter in design.infrastructure.subscribers:
        ports += [
            PortDecl(status_port(converter.id, reason), Direction.OUT, COUNTER_BITS)
            for reason in DROP_REASONS
        ]
    ports += busy_port(design)
    return EntityDecl(top_name(design), tuple(ports))


def _wire_dma(builder: TopBuilder, label: str, converter: Converter, side: Side) -> None:
    """Join a converter's DMA side to its group on the manager."""
    if side is Side.SUBSCRIBER:
        group, bus = f"sub{converter.id}", "s_axis"
        for signal in ("tdata", "tkeep", "tvalid", "tlast"):
            builder.wire(Terminal(MANAGER, f"{group}_{signal}"), Terminal(label, f"{bus}_{signal}"))
        builder.wire(Terminal(label, f"{bus}_tready"), Terminal(MANAGER, f"{group}_tready"))
        return
    group, bus = f"pub{converter.id}", "m_axis"
    for signal in ("tdata", "tkeep", "tvalid", "tlast"):
        builder.wire(Terminal(label, f"{bus}_{signal}"), Terminal(MANAGER, f"{group}_{signal}"))
    builder.wire(Terminal(MANAGER, f"{group}_tready"), Terminal(label, f"{bus}_tready"))
    builder.wire(Terminal(label, "frame_length"), Terminal(MANAGER, f"{group}_length"))


def _slice_label(into: Endpoint) -> str:
    """The register slice in front of a block's input port."""
    return f"{identifier(into.block)}_{identifier(into.port or 'in')}_slice"


def _fan_out(
    builder: TopBuilder,
    source: Interface,
    targets: list[Interface],
    fork: EntityDecl,
    what: str,
) -> None:
    """One message to several blocks: fields shared, the handshake through a fork.

    Each target is a register slice (as a single consumer's is), so what the fork hands on and
    the readies it combines come from flip-flops. check-hardware has refused strings and
    sequences here: a fork shares no sub-stream.
    """
    valid, ready = f"{MESSAGE}_valid", f"{MESSAGE}_ready"
    label = f"{source[valid].cell}_{source[valid].port}_fork"
    builder.cell(label, fork)
    builder.wire(source[valid], Terminal(label, "s_valid"))
    builder.wire(Terminal(label, "s_ready"), source[ready])
    for index, target in enumerate(targets):
        builder.wire(Terminal(label, f"m{index}_valid"), target[valid])
        builder.wire(target[ready], Terminal(label, f"m{index}_ready"))
        fields = {n: t for n, t in target.items() if n not in (valid, ready)}
        wire_connection(builder, source, fields, what)


def _tie_unused_readies(builder: TopBuilder) -> None:
    """A ready no destination drives takes every beat: that part of the message is unused."""
    for label, entity in builder.cells():
        for port in entity.ports:
            terminal = Terminal(label, port.name)
            unused = port.mode is Direction.IN and port.wire and port.name.endswith("ready")
            if unused and not builder.driven(terminal):
                builder.connect(terminal, constant(1, 1, wire=True))


def _preemptive(spec: AnySchedulerSpec) -> bool:
    if isinstance(spec, SchedulerSpec):
        return spec.algorithm.preemptive
    return _preemptive(spec.parent) or any(_preemptive(c) for c in spec.children)
