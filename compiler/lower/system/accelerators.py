"""Accelerators in the logic: how a block of each accelerator type is built and wired.

Every kind ends as `AcceleratorHardware`: the cells a block of the type instantiates, the wires
between them, and where each of its message pins (`rfc.lower.system.interfaces`) is. MyHDL
blocks are elaborated with the convention's port signals and converted; VHDL entities are read
with GHDL's parser and checked against the convention; an HLS top function becomes the Vitis
HLS core (an IP cell) beside rfc's ap_ctrl wrapper (`rfc.lib.hls.adapter`): the core reads its
fixed inputs straight from the subscribers' fields, the wrapper drives its control, adapts its
streams and lengths (`rfc.hls.ports` names the core's ports) and holds its outputs.
Cell ports named ``clk``/``ap_clk`` go on the clock, ``rst``/``ap_rst`` on the reset.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from rfc.errors import RfcError
from rfc.hls.ports import (
    CorePort,
    CoreStream,
    accelerator_core,
    input_holds,
    vitis_directives,
)
from rfc.ir.model import AcceleratorKind, AcceleratorType, Block
from rfc.lib.converters.ports import Direction, Port, PortRole
from rfc.lib.hls.adapter import AdapterShape, StreamPort
from rfc.lib.interface import typed_block
from rfc.lower.netlist import EntityDecl, PortDecl
from rfc.lower.system.components import (
    Component,
    adapter_component,
    convert,
    synthesized_netlist,
)
from rfc.lower.system.interfaces import MESSAGE, Pin, accelerator_pins
from rfc.lower.system.latency import accelerator_latency
from rfc.messages.limits import Limits
from rfc.passes.check_hardware import (
    CLOCK,
    RESET,
    block_function,
    flat_ports,
    takes_interfaces,
    vhdl_entity,
)
from rfc.user_code import running_user_code

#: The Vitis HLS cores' control ports (``ap_ctrl_hs``).
_HLS_CONTROL = (
    PortDecl("ap_clk", Direction.IN, 1, True),
    PortDecl("ap_rst", Direction.IN, 1, True),
    PortDecl("ap_start", Direction.IN, 1, True),
    PortDecl("ap_done", Direction.OUT, 1, True),
    PortDecl("ap_idle", Direction.OUT, 1, True),
    PortDecl("ap_ready", Direction.OUT, 1, True),
)
#: A core's ap_fifo ports, for an output stream (True) and an input one: (suffix, the core's
#: mode, whether it carries an element rather than one bit).
_FIFO_PORTS = {
    True: (
        ("din", Direction.OUT, True),
        ("full_n", Direction.IN, False),
        ("write", Direction.OUT, False),
    ),
    False: (
        ("dout", Direction.IN, True),
        ("empty_n", Direction.IN, False),
        ("read", Direction.OUT, False),
    ),
}
#: Prefix of the ap_ctrl wrapper's inputs from the core's outputs.
_CORE_SIDE = "core_"


@dataclass(frozen=True)
class HlsCore:
    """An HLS accelerator's core, for the Vitis HLS script.

    Attributes:
        accelerator: The accelerator type's name.
        top: The top function.
        sources: Its C++ sources.
        directives: Vitis HLS directives (tcl) that give the core its ports
            (`rfc.hls.ports.vitis_directives`).
    """

    accelerator: str
    top: str
    sources: tuple[Path, ...]
    directives: tuple[str, ...] = ()


@dataclass(frozen=True)
class AcceleratorHardware:
    """How a block of one accelerator type appears in the logic.

    Attributes:
        components: Entities to compile for it (none for a vendor core).
        cells: ``(suffix, entity)`` per cell of a block; the block's cell is labelled with the
            block's name, followed by ``_suffix`` when the suffix is not empty.
        wires: ``(source suffix, output, destination suffix, input)`` between its cells.
        pins: ``(accelerator port, converter-side name)`` → ``(suffix, cell port)``.
        hls: The HLS core, for HLS accelerators.
        latency: Measures the cycles from inputs to outputs (MyHDL accelerators, which rfc
            can simulate by itself), or None.
    """

    components: tuple[Component, ...]
    cells: tuple[tuple[str, EntityDecl], ...]
    wires: tuple[tuple[str, str, str, str], ...] = ()
    pins: Mapping[tuple[str, str], tuple[str, str]] = field(default_factory=dict)
    hls: HlsCore | None = None
    latency: Callable[[], int | None] | None = field(default=None, compare=False)


def accelerator_hardware(
    accelerator: AcceleratorType, block: Block, width: int, limits: Limits, directory: Path
) -> AcceleratorHardware:
    """Build the hardware of an accelerator type, using one of its blocks for the port layouts.

    Raises:
        RfcError: The accelerator's source does not follow the port convention, or is ROS-SW.
    """
    ports = {port.name: accelerator_pins(port, width, limits) for port in block.ports}
    builder = _BUILDERS.get(accelerator.kind)
    if builder is None:
        kinds = ", ".join(kind.value for kind in _BUILDERS)
        raise RfcError(
            f"accelerator '{accelerator.name}' is {accelerator.kind.value}, which has no "
            f"hardware; the kinds in the logic are {kinds}",
            location=accelerator.location,
        )
    return builder(accelerator, block, ports, directory, width, limits)


def entity_name(accelerator: AcceleratorType) -> str:
    """The entity rfc generates for an accelerator type (lower case, as VHDL folds it)."""
    return accelerator.name.lower()


def _convention(ports: Mapping[str, tuple[Pin, ...]]) -> list[PortDecl]:
    return [
        PortDecl(CLOCK, Direction.IN, 1, True),
        PortDecl(RESET, Direction.IN, 1, True),
        *(pin.port for pins in ports.values() for pin in pins),
    ]


def _own_pins(ports: Mapping[str, tuple[Pin, ...]]) -> dict[tuple[str, str], tuple[str, str]]:
    return {
        (port, pin.role_name): ("", pin.port.name) for port, pins in ports.items() for pin in pins
    }


def _myhdl(
    accelerator: AcceleratorType, ports: Mapping[str, tuple[Pin, ...]], directory: Path
) -> AcceleratorHardware:
    function = block_function(accelerator)
    declared = _convention(ports)
    name = entity_name(accelerator)
    signatures = {port: tuple(pin.signal for pin in pins) for port, pins in ports.items()}
    if takes_interfaces(accelerator, function, signatures):
        function = typed_block(function, signatures, f"{name}_interfaces")
    signals = [_signal_port(d) for d in declared]
    try:
        with running_user_code(f"converting MyHDL accelerator '{accelerator.name}'"):
            component = convert(
                name, signals, function, directory, f"MyHDL accelerator {accelerator.name}"
            )
    except RfcError:
        raise
    except Exception as exc:  # the user's block failed to elaborate or convert: say where
        sources = ", ".join(p.name for p in accelerator.sources) or "its source"
        raise RfcError(
            f"MyHDL accelerator '{accelerator.name}' (block '{accelerator.top}' in {sources}) "
            f"failed to convert: {type(exc).__name__}: {exc}",
            location=accelerator.location,
            hint=f"`rfc stub SPEC {accelerator.name} --lang myhdl` prints the interface objects "
            "it is given, member by member",
        ) from None
    _check_driven(accelerator, ports, component.files[-1])
    inputs = [
        p
        for p in ports
        if any(
            pin.port.mode is Direction.IN and pin.role_name == f"{MESSAGE}_valid"
            for pin in ports[p]
        )
    ]
    outputs = [p for p in ports if p not in inputs]

    def latency() -> int | None:
        return accelerator_latency(function, signals, inputs, outputs)

    return AcceleratorHardware(
        (component,), (("", component.entity),), pins=_own_pins(ports), latency=latency
    )


_PORT_MODE = re.compile(r"^\s*(\w+)\s*:\s*(in|out|inout)\b", re.M)


def _check_driven(
    accelerator: AcceleratorType, ports: Mapping[str, tuple[Pin, ...]], vhdl: Path
) -> None:
    """Refuse outputs the block never drives: MyHDL declares those as inputs.

    Raises:
        RfcError: Naming the first undriven output by its interface-object member.
    """
    entity = vhdl.read_text(encoding="utf-8").split("architecture", 1)[0]
    modes = dict(_PORT_MODE.findall(entity))
    for port, pins in ports.items():
        for pin in pins:
            if pin.port.mode is Direction.OUT and modes.get(pin.port.name) != "out":
                member = port + "".join(
                    f"[{step}]" if isinstance(step, int) else f".{step}"
                    for step in pin.signal.member
                )
                raise RfcError(
                    f"MyHDL accelerator '{accelerator.name}' never drives {member} (port "
                    f"{pin.port.name}), an output of its messages",
                    location=accelerator.location,
                    hint=f"drive it, with a constant if it does not matter ({member}.next = 0 "
                    "in a clocked process)",
                )


def _signal_port(declared: PortDecl) -> Port:
    """A converter-convention port for `port_signals`: wires become bool signals."""
    direction = Direction.IN if declared.mode is Direction.IN else Direction.OUT
    if declared.name == RESET:
        role = PortRole.RESET
    elif declared.wire:
        role = PortRole.VALID
    else:
        role = PortRole.FIELD
    return Port(declared.name, declared.bits, direction, role)


def _vhdl(
    accelerator: AcceleratorType, ports: Mapping[str, tuple[Pin, ...]], directory: Path
) -> AcceleratorHardware:
    signatures = {port: tuple(pin.signal for pin in pins) for port, pins in ports.items()}
    found = vhdl_entity(accelerator, flat_ports(signatures))
    entity = EntityDecl(found.name, tuple(_convention(ports)))
    netlist = synthesized_netlist(tuple(accelerator.sources), found.name, directory)
    component = Component(
        entity, tuple(accelerator.sources), verilog=netlist, verilog_by_ghdl=bool(netlist)
    )
    return AcceleratorHardware((component,), (("", entity),), pins=_own_pins(ports))


def _hls(
    accelerator: AcceleratorType,
    block: Block,
    ports: Mapping[str, tuple[Pin, ...]],
    directory: Path,
    width: int,
    limits: Limits,
) -> AcceleratorHardware:
    top = accelerator.top or accelerator.name
    signatures = {port: tuple(pin.signal for pin in pins) for port, pins in ports.items()}
    arguments, interface = accelerator_core(accelerator, signatures)
    wiring = _HlsWiring({pin.signal.name: pin for pins in ports.values() for pin in pins})
    for core_port in interface.ports:
        wiring.add_field(core_port)
    for stream in interface.streams:
        wiring.add_stream(stream)
    for port in block.ports:
        wiring.pins[(port.name, f"{MESSAGE}_valid")] = ("control", f"{port.name}_valid")
        wiring.pins[(port.name, f"{MESSAGE}_ready")] = ("control", f"{port.name}_ready")
    depths = {
        (port, buffer.path): buffer.words for port, buffer in input_holds(block, width, limits)
    }
    held = [s for s in interface.streams if (s.message_port, s.path) in depths]
    sources = {s.message_port: s for s in interface.streams if not s.output and s not in held}
    shape = AdapterShape(
        tuple(p.name for p in block.inputs),
        tuple((p.name, tuple(wiring.outputs.get(p.name, ()))) for p in block.outputs),
        tuple(_stream_in(sources.get(p.name)) for p in block.inputs),
        tuple(_stream_out(s) for s in interface.streams if s.output),
        tuple(wiring.lengths),
        tuple(_stream_out(s, depths[(s.message_port, s.path)]) for s in held),
    )
    adapter = adapter_component(shape, directory, f"{entity_name(accelerator)}_ap_ctrl")
    core = EntityDecl(top, tuple(wiring.core), vlnv=f"xilinx.com:hls:{top}:1.0")
    return AcceleratorHardware(
        (adapter,),
        (("core", core), ("control", adapter.entity)),
        tuple(wiring.wires),
        wiring.pins,
        HlsCore(
            accelerator.name,
            top,
            tuple(accelerator.sources),
            vitis_directives(top, arguments, signatures),
        ),
    )


@dataclass
class _HlsWiring:
    """The core's ports and the wires between the core, the wrapper and the message pins."""

    by_field: Mapping[str, Pin]
    core: list[PortDecl] = field(default_factory=lambda: list(_HLS_CONTROL))
    wires: list[tuple[str, str, str, str]] = field(
        default_factory=lambda: [
            ("control", "ap_start", "core", "ap_start"),
            *(("core", n, "control", n) for n in ("ap_done", "ap_idle", "ap_ready")),
        ]
    )
    pins: dict[tuple[str, str], tuple[str, str]] = field(default_factory=dict)
    outputs: dict[str, list[tuple[str, str, int, int]]] = field(default_factory=dict)
    lengths: list[tuple[str, str, int, int]] = field(default_factory=list)

    def add_field(self, port: CorePort) -> None:
        """A field or length: straight into the core, or through the wrapper."""
        pin = self.by_field[port.field]
        name, bits = port.core, port.core_bits
        held = f"{_CORE_SIDE}{name}"  # the wrapper's name: a member's may be the field's
        if port.output:
            self.core += [
                PortDecl(name, Direction.OUT, bits),
                PortDecl(f"{name}_ap_vld", Direction.OUT, 1, True),
            ]
            self.outputs.setdefault(port.message_port, []).append(
                (pin.port.name, held, port.bits, bits)
            )
            self.wires += [
                ("core", name, "control", held),
                ("core", f"{name}_ap_vld", "control", f"{held}_ap_vld"),
            ]
            self.pins[(port.message_port, pin.role_name)] = ("control", pin.port.name)
        elif port.length:  # widened to the core's uint32_t by the wrapper
            self.core.append(PortDecl(name, Direction.IN, bits))
            self.lengths.append((pin.port.name, held, port.bits, bits))
            self.wires.append(("control", held, "core", name))
            self.pins[(port.message_port, pin.role_name)] = ("control", pin.port.name)
        else:
            self.core.append(PortDecl(name, Direction.IN, bits))
            self.pins[(port.message_port, pin.role_name)] = ("core", name)

    def add_stream(self, stream: CoreStream) -> None:
        """A stream: its sub-stream pins on the wrapper, its ap_fifo between wrapper and core."""
        for suffix in ("tdata", "tkeep", "tvalid", "tready", "tlast"):
            pin = self.by_field.get(f"{stream.stream}_{suffix}")
            if pin is not None:
                self.pins[(stream.message_port, pin.role_name)] = ("control", pin.port.name)
        arg, held = stream.core, f"{_CORE_SIDE}{stream.core}"
        for suffix, mode, data in _FIFO_PORTS[stream.output]:
            self.core.append(
                PortDecl(f"{arg}_{suffix}", mode, stream.element if data else 1, not data)
            )
            core, wrapper = ("core", f"{arg}_{suffix}"), ("control", f"{held}_{suffix}")
            self.wires.append((*core, *wrapper) if mode is Direction.OUT else (*wrapper, *core))


def _stream_in(stream: CoreStream | None) -> StreamPort | None:
    if stream is None:
        return None
    return StreamPort(stream.stream, f"{_CORE_SIDE}{stream.core}", stream.element, stream.beat)


def _stream_out(stream: CoreStream, depth: int = 0) -> StreamPort:
    core = f"{_CORE_SIDE}{stream.core}"
    return StreamPort(stream.stream, core, stream.element, stream.beat, depth)


#: Builds the hardware of an accelerator type: (type, a block of it, its pins, output folder,
#: bus width, maxima).
HardwareBuilder = Callable[
    [AcceleratorType, Block, Mapping[str, tuple[Pin, ...]], Path, int, Limits],
    AcceleratorHardware,
]
#: The accelerator kinds that become logic, each with its builder.
_BUILDERS: dict[AcceleratorKind, HardwareBuilder] = {
    AcceleratorKind.MYHDL: lambda accelerator, _, ports, directory, *__: _myhdl(
        accelerator, ports, directory
    ),
    AcceleratorKind.VHDL: lambda accelerator, _, ports, directory, *__: _vhdl(
        accelerator, ports, directory
    ),
    AcceleratorKind.HLS: _hls,
}
