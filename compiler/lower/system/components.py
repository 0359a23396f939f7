"""The entities of the logic that rfc generates itself, converted from MyHDL to VHDL and Verilog.

Each is a `Component`: its interface as the netlist sees it, its VHDL files and its Verilog
file, both from MyHDL's converters (the same module and port names). The converters
come from `rfc.lib.converters`, the manager from `rfc.lib.manager`, the ap_ctrl wrapper of HLS
cores from `rfc.lib.hls`, the handshake fork of fan-out from `rfc.lib.fork`, the gate and the
guard that drop malformed frames from `rfc.lib.converters.malformed` and `.guard`.
"""

from __future__ import annotations

import dataclasses
import tempfile
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from myhdl import ToVerilogWarning, ToVHDLWarning

from rfc.ir.infrastructure import Converter
from rfc.lib.arith.timing import known_block
from rfc.lib.converters.buffers import Buffer, buffered_ports, buffered_publisher, buffers_of
from rfc.lib.converters.build import generate, publisher_top, subscriber_top
from rfc.lib.converters.guard import frame_guard, guard_ports
from rfc.lib.converters.malformed import drop_gate, gate_ports
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Direction, Port, PortRole, Side, dma_ports, ports_of
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.lib.fork import fork_body
from rfc.lib.hls.adapter import AdapterShape, hls_adapter
from rfc.lib.manager.entity import ManagerShape, manager_ports, manager_top
from rfc.lib.slice import slice_body
from rfc.lower.netlist import EntityDecl
from rfc.lower.system.conversion_cache import converted
from rfc.lower.system.interfaces import declaration
from rfc.messages.limits import Limits
from rfc.toolchain import GhdlError, convert_myhdl, elaboration, synthesize_verilog


@dataclass(frozen=True)
class Component:
    """An entity the top level instantiates.

    Attributes:
        entity: Its interface.
        files: Its VHDL files in compile order (MyHDL's package first, where it needs one).
        buffers: The FIFOs it holds for a message's strings and sequences.
        verilog: Its Verilog files (none for a VHDL accelerator until GHDL synthesizes it,
            nor for a vendor core).
        verilog_by_ghdl: Whether `verilog` is GHDL's netlist of VHDL (whose Verilog writer
            has known bugs: fine for Yosys's estimate, not for simulation).
        myhdl: The MyHDL block it was converted from, taking its port signals by name (none
            for a VHDL accelerator or a vendor core): ``rfc sim --backend myhdl`` runs it.
    """

    entity: EntityDecl
    files: tuple[Path, ...] = ()
    buffers: tuple[Buffer, ...] = ()
    verilog: tuple[Path, ...] = ()
    verilog_by_ghdl: bool = False
    myhdl: Callable[..., Any] | None = dataclasses.field(default=None, compare=False)


def _component(
    entity: EntityDecl, files: Sequence[Path], myhdl: Callable[..., Any] | None = None
) -> Component:
    """A component from MyHDL's output: VHDL files first, then the Verilog file."""
    return Component(
        entity,
        tuple(f for f in files if f.suffix == ".vhd"),
        verilog=tuple(f for f in files if f.suffix == ".v"),
        myhdl=myhdl,
    )


def entity_of(name: str, ports: Sequence[Port]) -> EntityDecl:
    """The netlist's view of an entity declared with converter-convention ports."""
    return EntityDecl(name, tuple(declaration(port) for port in ports))


def convert(
    name: str,
    ports: Sequence[Port],
    body: Callable[..., Any],
    directory: Path,
    what: str,
    **parameters: Any,
) -> Component:
    """Elaborate ``body(**parameters, **ports)`` as entity `name`; convert to VHDL and Verilog."""
    top = top_block(name, [p.name for p in ports], body, **parameters)

    def conversion() -> list[Path]:
        with elaboration(), _quiet_conversion():
            instance = top(**port_signals(ports))
            files: list[Path] = convert_myhdl(
                instance, name, directory, header=f"{name}: {what}", separate=known_block
            )
        return files

    return _component(entity_of(name, ports), converted(name, directory, conversion), top)


@contextmanager
def _quiet_conversion() -> Iterator[None]:
    """MyHDL notes every unread or constant internal signal; generated designs have many."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ToVHDLWarning)
        warnings.simplefilter("ignore", ToVerilogWarning)
        warnings.simplefilter("ignore", UserWarning)
        yield


def synthesized_netlist(sources: Sequence[Path], top: str, directory: Path) -> tuple[Path, ...]:
    """A VHDL entity's Verilog as GHDL synthesizes it, or none when GHDL cannot.

    MyHDL's back-ends do not read VHDL, so GHDL's synthesis is the only way to give a VHDL
    accelerator a Verilog view; an entity it refuses stays VHDL (the report says which).
    """
    target = directory / f"{top}.v"
    try:
        with tempfile.TemporaryDirectory(prefix="rfc-ghdl-") as scratch:
            text = synthesize_verilog(sources, top, Path(scratch))
    except GhdlError:
        return ()
    target.write_text(f"// {top}: GHDL's synthesized netlist of a VHDL accelerator\n{text}")
    return (target,)


def converter_component(
    converter: Converter,
    side: Side,
    directory: Path,
    name: str,
    limits: Limits,
    record_first: bool = False,
) -> Component:
    """A subscriber or publisher converter of the model.

    A publisher that takes strings or sequences comes with its buffers (`rfc.lib.converters.
    buffers`): the producer may hand them over before the message's record. Behind a
    record-first producer the message's last stream needs none (`Plan.streamed_last`).
    """
    converter_plan = replace(
        plan(converter.layout, converter.bus_width, limits), record_first=record_first
    )
    buffers = buffers_of(converter_plan) if side is Side.PUBLISHER else ()
    if buffers:
        what = f"publisher of {converter.layout.display_name} with its buffers (rfc)"
        ports = buffered_ports(converter_plan)
        component = convert(name, ports, buffered_publisher, directory, what, plan=converter_plan)
        return replace(component, buffers=buffers)
    ports = (*dma_ports(converter_plan, side), *ports_of(converter_plan, side))

    def conversion() -> tuple[Path, ...]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            return generate(converter_plan, side, directory, name).files

    top = subscriber_top if side is Side.SUBSCRIBER else publisher_top
    files = converted(name, directory, conversion)
    return _component(entity_of(name, ports), files, top(converter_plan, name))


def manager_component(shape: ManagerShape, directory: Path, name: str) -> Component:
    """The manager: PS→PL demultiplexer and PL→PS multiplexer with its scheduler."""
    ports = manager_ports(shape)
    top = manager_top(shape, name)

    def conversion() -> list[Path]:
        with elaboration(), _quiet_conversion():
            instance = top(**port_signals(ports))
            header = f"{name}: the DMA manager of the system (rfc)"
            files: list[Path] = convert_myhdl(instance, name, directory, header=header)
        return files

    return _component(entity_of(name, ports), converted(name, directory, conversion), top)


def fork_component(consumers: int, directory: Path, name: str) -> Component:
    """A handshake fork to `consumers` consumers."""
    ports = [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
        Port("s_valid", 1, Direction.IN, PortRole.VALID),
        Port("s_ready", 1, Direction.OUT, PortRole.READY),
    ]
    for index in range(consumers):
        ports += [
            Port(f"m{index}_valid", 1, Direction.OUT, PortRole.VALID),
            Port(f"m{index}_ready", 1, Direction.IN, PortRole.READY),
        ]
    what = f"handshake fork to {consumers} (rfc)"
    return convert(name, ports, fork_body, directory, what, consumers=consumers)


#: The ROS type that makes a one-bit field port a ``std_logic``.
_BOOL = "bool"


def slice_component(
    fields: tuple[tuple[str, int, bool], ...], directory: Path, name: str
) -> Component:
    """A register slice over a message's fields (name, width, single bit) and its handshake."""
    ports = [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
        Port("s_valid", 1, Direction.IN, PortRole.VALID),
        Port("s_ready", 1, Direction.OUT, PortRole.READY),
        Port("m_valid", 1, Direction.OUT, PortRole.VALID),
        Port("m_ready", 1, Direction.IN, PortRole.READY),
    ]
    for side, direction in (("s", Direction.IN), ("m", Direction.OUT)):
        ports += [
            Port(
                f"{side}_{field}", bits, direction, PortRole.FIELD, ros_type="bool" if one else None
            )
            for field, bits, one in fields
        ]
    what = f"register slice of a message of {len(fields)} fields (rfc)"
    return convert(name, ports, slice_body, directory, what, fields=fields)


def gate_component(directory: Path, name: str) -> Component:
    """The gate that takes a subscriber's malformed frames and counts them by reason."""
    what = "drops and counts malformed frames (rfc)"
    return convert(name, gate_ports(), drop_gate, directory, what)


def guard_component(converters: Plan, depth: int, directory: Path, name: str) -> Component:
    """The store-and-forward guard of one subscriber, with a buffer of `depth` beats."""
    what = f"store-and-forward check of {converters.layout.display_name} frames (rfc)"
    ports = guard_ports(converters.width)
    return convert(name, ports, frame_guard, directory, what, plan=converters, depth=depth)


def adapter_component(shape: AdapterShape, directory: Path, name: str) -> Component:
    """The ap_ctrl wrapper of one HLS core."""
    ports = adapter_ports(shape)
    return convert(name, ports, hls_adapter, directory, "ap_ctrl wrapper (rfc)", shape=shape)


def adapter_ports(shape: AdapterShape) -> list[Port]:
    """The ap_ctrl wrapper's ports, in declaration order."""
    into, out = Direction.IN, Direction.OUT
    ports = [
        Port("clk", 1, into, PortRole.CLOCK),
        Port("rst", 1, into, PortRole.RESET),
        Port("ap_start", 1, out, PortRole.VALID),
        Port("ap_done", 1, into, PortRole.VALID),
        Port("ap_idle", 1, into, PortRole.VALID),
        Port("ap_ready", 1, into, PortRole.READY),
    ]
    for port in shape.inputs:
        ports += [
            Port(f"{port}_valid", 1, into, PortRole.VALID),
            Port(f"{port}_ready", 1, out, PortRole.READY),
        ]
    for port, fields in shape.outputs:
        for field, core, bits, core_bits in fields:
            ports += [
                Port(core, core_bits, into, PortRole.FIELD),
                Port(f"{core}_ap_vld", 1, into, PortRole.VALID),
                Port(field, bits, out, PortRole.FIELD),
            ]
        ports += [
            Port(f"{port}_valid", 1, out, PortRole.VALID),
            Port(f"{port}_ready", 1, into, PortRole.READY),
        ]
    for field, core, bits, core_bits in shape.lengths:
        ports += [
            Port(field, bits, into, PortRole.FIELD),
            Port(core, core_bits, out, PortRole.FIELD),
        ]
    for source in (*(s for s in shape.sources if s is not None), *shape.held):
        s, c = source.stream, source.core
        ports += [
            Port(f"{s}_tdata", source.beat, into, PortRole.TDATA),
            Port(f"{s}_tkeep", source.beat // 8, into, PortRole.TKEEP),
            Port(f"{s}_tvalid", 1, into, PortRole.TVALID),
            Port(f"{s}_tready", 1, out, PortRole.TREADY),
            Port(f"{s}_tlast", 1, into, PortRole.TLAST),
            Port(f"{c}_dout", source.element, out, PortRole.FIELD),
            Port(f"{c}_empty_n", 1, out, PortRole.VALID),
            Port(f"{c}_read", 1, into, PortRole.READY),
        ]
    for sink in shape.sinks:
        s, c = sink.stream, sink.core
        ports += [
            Port(f"{c}_din", sink.element, into, PortRole.FIELD),
            Port(f"{c}_full_n", 1, out, PortRole.READY),
            Port(f"{c}_write", 1, into, PortRole.VALID),
            Port(f"{s}_tdata", sink.beat, out, PortRole.TDATA),
            Port(f"{s}_tvalid", 1, out, PortRole.TVALID),
            Port(f"{s}_tready", 1, into, PortRole.TREADY),
        ]
    return ports
