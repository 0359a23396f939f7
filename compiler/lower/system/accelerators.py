"""Accelerators in the logic: how a block of each accelerator type is built and wired.

Every kind ends as `AcceleratorHardware`: the cells a block of the type instantiates, the wires
between them, and where each of its message pins (`rfc.lower.system.interfaces`) is. MyHDL
blocks are elaborated with the convention's port signals and converted; VHDL entities are read
with GHDL's parser and checked against the convention; an HLS top function becomes the Vitis
HLS core (an IP cell) beside rfc's ap_ctrl wrapper (`rfc.lib.hls.adapter`): the core reads its
inputs straight from the subscribers' fields, the wrapper drives its control and holds its
outputs. Cell ports named ``clk``/``ap_clk`` go on the clock, ``rst``/``ap_rst`` on the reset.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rfc.errors import RfcError
from rfc.ir.model import AcceleratorKind, AcceleratorType, Block
from rfc.ir.model import Port as ModelPort
from rfc.lib.converters.ports import Direction, Port, PortRole
from rfc.lib.hls.adapter import AdapterShape
from rfc.lower.hls_signature import HlsArgument, read_top_function
from rfc.lower.netlist import EntityDecl, Mode, PortDecl
from rfc.lower.system.components import (
    Component,
    adapter_component,
    convert,
    synthesized_netlist,
)
from rfc.lower.system.interfaces import MESSAGE, Pin, accelerator_pins
from rfc.lower.system.latency import accelerator_latency
from rfc.messages.limits import Limits
from rfc.spec.python_sources import function_in
from rfc.toolchain import GhdlError, read_entities

#: Ports every accelerator has besides its message pins.
CLOCK, RESET = "clk", "rst"
#: The Vitis HLS cores' control ports (``ap_ctrl_hs``).
_HLS_CONTROL = (
    PortDecl("ap_clk", Mode.IN, 1, True),
    PortDecl("ap_rst", Mode.IN, 1, True),
    PortDecl("ap_start", Mode.IN, 1, True),
    PortDecl("ap_done", Mode.OUT, 1, True),
    PortDecl("ap_idle", Mode.OUT, 1, True),
    PortDecl("ap_ready", Mode.OUT, 1, True),
)


_ARGUMENT_ORDER = "inputs' fields by value, then outputs' fields by pointer (docs/accelerators.md)"


@dataclass(frozen=True)
class HlsCore:
    """An HLS accelerator's core, for the Vitis HLS script: top function and its sources."""

    accelerator: str
    top: str
    sources: tuple[Path, ...]


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
    if accelerator.kind is AcceleratorKind.MYHDL:
        return _myhdl(accelerator, ports, directory)
    if accelerator.kind is AcceleratorKind.VHDL:
        return _vhdl(accelerator, ports, directory)
    if accelerator.kind is AcceleratorKind.HLS:
        return _hls(accelerator, block, ports, directory)
    raise RfcError(f"accelerator '{accelerator.name}' is ROS-SW: it has no hardware")


def entity_name(accelerator: AcceleratorType) -> str:
    """The entity rfc generates for an accelerator type (lower case, as VHDL folds it)."""
    return accelerator.name.lower()


def _convention(ports: Mapping[str, tuple[Pin, ...]]) -> list[PortDecl]:
    return [
        PortDecl(CLOCK, Mode.IN, 1, True),
        PortDecl(RESET, Mode.IN, 1, True),
        *(pin.port for pins in ports.values() for pin in pins),
    ]


def _own_pins(ports: Mapping[str, tuple[Pin, ...]]) -> dict[tuple[str, str], tuple[str, str]]:
    return {
        (port, pin.role_name): ("", pin.port.name) for port, pins in ports.items() for pin in pins
    }


def _myhdl(
    accelerator: AcceleratorType, ports: Mapping[str, tuple[Pin, ...]], directory: Path
) -> AcceleratorHardware:
    function = _block_function(accelerator)
    declared = _convention(ports)
    _check_signature(accelerator, function, [d.name for d in declared])
    name = entity_name(accelerator)
    signals = [_signal_port(d) for d in declared]
    component = convert(name, signals, function, directory, f"MyHDL accelerator {accelerator.name}")
    inputs = [
        p
        for p in ports
        if any(pin.port.mode is Mode.IN and pin.role_name == f"{MESSAGE}_valid" for pin in ports[p])
    ]
    outputs = [p for p in ports if p not in inputs]

    def latency() -> int | None:
        return accelerator_latency(function, signals, inputs, outputs)

    return AcceleratorHardware(
        (component,), (("", component.entity),), pins=_own_pins(ports), latency=latency
    )


def _block_function(accelerator: AcceleratorType) -> Any:
    if accelerator.block_function is not None:
        return accelerator.block_function
    python = next(p for p in accelerator.sources if p.suffix == ".py")
    function = function_in(python, accelerator.top or accelerator.name, accelerator, "MyHDL block")
    definition = getattr(function, "definition", None)  # an @rfc.accelerator in a YAML project
    return getattr(definition, "block_function", None) or function


def _check_signature(accelerator: AcceleratorType, function: Any, expected: list[str]) -> None:
    plain = getattr(function, "func", function)  # MyHDL's @block keeps the function in .func
    try:
        parameters = inspect.signature(plain).parameters
    except (TypeError, ValueError):
        return
    keywords = any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values())
    required = [
        n
        for n, p in parameters.items()
        if p.default is inspect.Parameter.empty and p.kind is not inspect.Parameter.VAR_KEYWORD
    ]
    missing = [] if keywords else [n for n in expected if n not in parameters]
    extra = [n for n in required if n not in expected]
    if missing or extra:
        problems = []
        if missing:
            problems.append(f"it lacks {', '.join(missing)}")
        if extra:
            problems.append(f"it also needs {', '.join(extra)}, which rfc does not provide")
        raise RfcError(
            f"MyHDL block '{plain.__name__}' of accelerator '{accelerator.name}' does not have "
            f"the ports of its messages: {'; '.join(problems)}",
            location=accelerator.location,
            hint=f"declare it as {plain.__name__}({', '.join(expected)}) (docs/accelerators.md)",
        )


def _signal_port(declared: PortDecl) -> Port:
    """A converter-convention port for `port_signals`: wires become bool signals."""
    direction = Direction.IN if declared.mode is Mode.IN else Direction.OUT
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
    top = (accelerator.top or accelerator.name).lower()
    found = None
    for source in accelerator.sources:
        try:
            entities = read_entities(source)
        except GhdlError as exc:
            raise RfcError(
                f"VHDL source '{source.name}' of accelerator '{accelerator.name}' does not "
                f"analyse:\n{exc}",
                location=accelerator.location,
            ) from None
        found = found or next((e for e in entities if e.name.lower() == top), None)
    if found is None:
        raise RfcError(
            f"no entity '{top}' in the VHDL sources of accelerator '{accelerator.name}'",
            location=accelerator.location,
            hint="name the entity with 'top:' or name it like the accelerator",
        )
    expected = _convention(ports)
    actual = {p.name: p for p in found.ports}
    problems = []
    for want in expected:
        have = actual.get(want.name.lower())
        if have is None:
            problems.append(f"no port {want.name} ({_describe(want)})")
        elif have.mode != want.mode.value or have.wire != want.wire or have.bits != want.bits:
            kind = "std_logic" if have.wire else f"{have.bits}-bit vector"
            problems.append(f"{have.name} is {have.mode} {kind}, expected {_describe(want)}")
    names = {d.name.lower() for d in expected}
    problems += [
        f"port {p.name} is not part of the convention" for p in found.ports if p.name not in names
    ]
    if problems:
        raise RfcError(
            f"entity {found.name} ({found.file.name}:{found.line}) of accelerator "
            f"'{accelerator.name}' does not have the ports of its messages: " + "; ".join(problems),
            location=accelerator.location,
            hint="docs/accelerators.md lists the ports an accelerator has for its messages",
        )
    entity = EntityDecl(found.name, tuple(expected))
    netlist = synthesized_netlist(tuple(accelerator.sources), found.name, directory)
    component = Component(
        entity, tuple(accelerator.sources), verilog=netlist, verilog_by_ghdl=bool(netlist)
    )
    return AcceleratorHardware((component,), (("", entity),), pins=_own_pins(ports))


def _describe(port: PortDecl) -> str:
    kind = "std_logic" if port.wire else f"std_logic_vector({port.bits - 1} downto 0)"
    return f"{port.mode.value} {kind}"


def _hls(
    accelerator: AcceleratorType,
    block: Block,
    ports: Mapping[str, tuple[Pin, ...]],
    directory: Path,
) -> AcceleratorHardware:
    top = accelerator.top or accelerator.name
    arguments = read_top_function(list(accelerator.sources), top)
    fields: list[tuple[ModelPort, Pin]] = []
    for port in block.ports:
        for pin in ports[port.name]:
            if pin.role in (PortRole.VALID, PortRole.READY) and pin.group == MESSAGE:
                continue
            if pin.role is not PortRole.FIELD or pin.group != MESSAGE:
                raise _hls_refusal(accelerator, port, pin, "a string or sequence")
            if pin.port.wire:
                raise _hls_refusal(accelerator, port, pin, "a bool")
            fields.append((port, pin))
    _check_arguments(accelerator, top, arguments, fields)
    core_ports = list(_HLS_CONTROL)
    shape_outputs: dict[str, list[tuple[str, str, int]]] = {}
    pins: dict[tuple[str, str], tuple[str, str]] = {}
    wires = [("control", n, "core", n) for n in ("ap_start",)]
    wires += [("core", n, "control", n) for n in ("ap_done", "ap_idle", "ap_ready")]
    for (port, pin), argument in zip(fields, arguments, strict=True):
        if argument.output:
            core_ports += [
                PortDecl(argument.name, Mode.OUT, argument.bits),
                PortDecl(f"{argument.name}_ap_vld", Mode.OUT, 1, True),
            ]
            shape_outputs.setdefault(port.name, []).append(
                (pin.port.name, argument.name, argument.bits)
            )
            wires += [
                ("core", argument.name, "control", argument.name),
                ("core", f"{argument.name}_ap_vld", "control", f"{argument.name}_ap_vld"),
            ]
            pins[(port.name, pin.role_name)] = ("control", pin.port.name)
        else:
            core_ports.append(PortDecl(argument.name, Mode.IN, argument.bits))
            pins[(port.name, pin.role_name)] = ("core", argument.name)
    inputs = tuple(p.name for p in block.inputs)
    for port in block.ports:
        pins[(port.name, f"{MESSAGE}_valid")] = ("control", f"{port.name}_valid")
        pins[(port.name, f"{MESSAGE}_ready")] = ("control", f"{port.name}_ready")
    shape = AdapterShape(
        inputs, tuple((p.name, tuple(shape_outputs.get(p.name, ()))) for p in block.outputs)
    )
    adapter = adapter_component(shape, directory, f"{entity_name(accelerator)}_ap_ctrl")
    core = EntityDecl(top, tuple(core_ports), vlnv=f"xilinx.com:hls:{top}:1.0")
    return AcceleratorHardware(
        (adapter,),
        (("core", core), ("control", adapter.entity)),
        tuple(wires),
        pins,
        HlsCore(accelerator.name, top, tuple(accelerator.sources)),
    )


def _hls_refusal(accelerator: AcceleratorType, port: ModelPort, pin: Pin, what: str) -> RfcError:
    return RfcError(
        f"HLS accelerator '{accelerator.name}': port '{port.name}' carries {what} "
        f"('{pin.role_name}'); rfc connects HLS cores through scalar arguments only",
        location=accelerator.location,
        hint=f"exclude it from port '{port.name}', or write the accelerator in MyHDL or VHDL",
    )


def _check_arguments(
    accelerator: AcceleratorType,
    top: str,
    arguments: tuple[HlsArgument, ...],
    fields: list[tuple[ModelPort, Pin]],
) -> None:
    expected = [
        f"{pin.port.bits}-bit {'output' if port.direction.value == 'out' else 'input'} "
        f"for {port.name}.{pin.role_name}"
        for port, pin in fields
    ]
    if len(arguments) != len(fields):
        raise RfcError(
            f"HLS top function {top} of accelerator '{accelerator.name}' has "
            f"{len(arguments)} arguments; its messages need {len(fields)}: " + ", ".join(expected),
            location=arguments[0].location if arguments else accelerator.location,
            hint=_ARGUMENT_ORDER,
        )
    for argument, (port, pin), want in zip(arguments, fields, expected, strict=True):
        output = port.direction.value == "out"
        if argument.output != output or argument.bits != pin.port.bits:
            kind = "output" if argument.output else "input"
            raise RfcError(
                f"argument '{argument.name}' of HLS top function {top} is a {argument.bits}-bit "
                f"{kind}; expected a {want}",
                location=argument.location,
                hint=_ARGUMENT_ORDER,
            )
