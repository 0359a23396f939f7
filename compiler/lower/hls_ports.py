"""How an HLS top function's arguments become the data ports of its Vitis HLS core.

Two forms of top function reach the logic (docs/accelerators.md, "HLS accelerators"):

* scalar arguments, one per selected field: the core's port is named like the argument;
* one message struct per port (`rfc.lower.hls_types`), inputs by value and outputs by pointer.
  The Vitis HLS run disaggregates each struct and completely partitions each of its arrays
  (`vitis_directives`), so that every scalar member becomes one port named
  ``<argument>_<member>`` (``state_O_T_EE_15``, ``sums_point_x``) — the name the message
  signature gives the same field, with the argument's name in front.

Inputs are ``ap_none`` ports, outputs ``<name>`` with ``<name>_ap_vld``: the ap_ctrl wrapper
(`rfc.lib.hls.adapter`) keeps the inputs steady from ``ap_start`` to ``ap_done`` and captures
each output when its ``_ap_vld`` pulses. Strings and sequences (``hls::stream``) are C-simulated
by ``rfc sim`` but not wired into the logic: `core_ports` refuses them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from rfc.errors import RfcError
from rfc.lib.converters.ports import Direction, Port, PortRole
from rfc.lib.converters.steps import ROOT
from rfc.lower.hls_signature import ArgumentKind, HlsArgument

#: How the scalar form orders its arguments.
SCALAR_ORDER = "inputs' fields by value, then outputs' fields by pointer (docs/accelerators.md)"
#: How the struct form orders its arguments.
STRUCT_ORDER = (
    "one struct per port in the spec's order, inputs by value and outputs by pointer, as "
    "<accelerator>_messages.h declares the function (`rfc stub SPEC ACCELERATOR --lang hls`)"
)


@dataclass(frozen=True)
class CorePort:
    """One data port of the Vitis core and the message field it carries.

    Attributes:
        message_port: The accelerator's port the field belongs to.
        field: The field's pin in the message signature (``state_q_0``).
        core: The core's port (``state_q_0``; a scalar argument's name).
        bits: Its width.
        output: The core drives it (with ``<core>_ap_vld``).
    """

    message_port: str
    field: str
    core: str
    bits: int
    output: bool


def core_ports(
    accelerator: str,
    top: str,
    arguments: Sequence[HlsArgument],
    signatures: Mapping[str, Sequence[Port]],
) -> tuple[CorePort, ...]:
    """Match the top function's arguments with the message fields, port by port.

    Args:
        accelerator: The accelerator type's name (for messages).
        top: The top function's name.
        arguments: Its arguments (`rfc.lower.hls_signature.read_top_function`).
        signatures: Per accelerator port, in the spec's order (inputs, then outputs), its
            message signature.

    Raises:
        RfcError: An argument that does not match its field or struct, a string or sequence
            (not wired into the logic), or a bool field.
    """
    for argument in arguments:
        if argument.kind is ArgumentKind.STREAM:
            raise RfcError(
                f"HLS top function {top} of accelerator '{accelerator}' takes "
                f"'{argument.ctype} &{argument.name}': rfc does not wire hls::stream arguments "
                "into the logic (`rfc sim` C-simulates them)",
                location=argument.location,
                hint="exclude the strings and sequences from the accelerator's ports, or write "
                "it in MyHDL or VHDL",
            )
    fields = [(port, pin) for port, pins in signatures.items() for pin in _fields(port, pins)]
    if any(a.kind is ArgumentKind.STRUCT for a in arguments):
        return _struct_ports(accelerator, top, arguments, signatures, fields)
    return _scalar_ports(accelerator, top, arguments, fields)


def vitis_directives(
    top: str, arguments: Sequence[HlsArgument], signatures: Mapping[str, Sequence[Port]]
) -> tuple[str, ...]:
    """The Vitis HLS directives (tcl) that give a core the ports `core_ports` names.

    Every argument gets its interface mode (``ap_none`` inputs, ``ap_vld`` outputs, as for
    scalars by default); a struct is disaggregated, and each array inside it (``state.q``,
    ``pose->covariance``) completely partitioned, so that each element is a port.

    Args:
        top: The top function's name.
        arguments: Its arguments, one struct per port when it takes structs.
        signatures: Per accelerator port, in the spec's order, its message signature.
    """
    lines = [f"set_directive_interface -mode ap_ctrl_hs {top} return"]
    structs = [a for a in arguments if a.kind is ArgumentKind.STRUCT]
    for argument in arguments:
        mode = "ap_vld" if argument.output else "ap_none"
        if argument.kind is ArgumentKind.STRUCT:
            lines.append(f"set_directive_disaggregate {top} {argument.name}")
        lines.append(f"set_directive_interface -mode {mode} {top} {argument.name}")
    for argument, pins in zip(structs, signatures.values(), strict=False):
        arrow = "->" if argument.output else "."
        arrays: dict[str, None] = {}
        for pin in pins:
            steps = pin.member
            index = next((i for i, s in enumerate(steps) if isinstance(s, int)), None)
            if pin.role is PortRole.FIELD and index:
                arrays[".".join(str(s) for s in steps[:index])] = None
        lines += [
            f"set_directive_array_partition -type complete -dim 0 {top} "
            f"{argument.name}{arrow}{array}"
            for array in arrays
        ]
    return tuple(lines)


def _fields(port: str, pins: Sequence[Port]) -> list[Port]:
    """The message's fields on a port; strings, sequences and bools refused."""
    fields = []
    for pin in pins:
        if pin.role in (PortRole.VALID, PortRole.READY) and pin.group == ROOT:
            continue
        if pin.role is not PortRole.FIELD or pin.group != ROOT:
            raise _refusal(port, pin, "a string or sequence")
        if pin.is_wire:
            raise _refusal(port, pin, "a bool")
        fields.append(pin)
    return fields


def _refusal(port: str, pin: Port, what: str) -> RfcError:
    path = pin.path or pin.name
    return RfcError(
        f"port '{port}' carries {what} ('{path}'), which rfc does not wire to an HLS core in "
        "the logic",
        hint=f"exclude '{path}' from port '{port}', or write the accelerator in MyHDL or VHDL",
    )


def _output(pin: Port) -> bool:
    return pin.direction is Direction.OUT


def _scalar_ports(
    accelerator: str, top: str, arguments: Sequence[HlsArgument], fields: list[tuple[str, Port]]
) -> tuple[CorePort, ...]:
    expected = [
        f"{pin.bits}-bit {'output' if _output(pin) else 'input'} for {port}.{pin.path}"
        for port, pin in fields
    ]
    if len(arguments) != len(fields):
        raise RfcError(
            f"HLS top function {top} of accelerator '{accelerator}' has {len(arguments)} "
            f"arguments; its messages need {len(fields)}: " + ", ".join(expected),
            location=arguments[0].location if arguments else None,
            hint=SCALAR_ORDER,
        )
    ports = []
    for argument, (port, pin), want in zip(arguments, fields, expected, strict=True):
        if argument.output != _output(pin) or argument.bits != pin.bits:
            kind = "output" if argument.output else "input"
            raise RfcError(
                f"argument '{argument.name}' of HLS top function {top} is a {argument.bits}-bit "
                f"{kind}; expected a {want}",
                location=argument.location,
                hint=SCALAR_ORDER,
            )
        ports.append(CorePort(port, pin.name, argument.name, pin.bits, argument.output))
    return tuple(ports)


def _struct_ports(
    accelerator: str,
    top: str,
    arguments: Sequence[HlsArgument],
    signatures: Mapping[str, Sequence[Port]],
    fields: list[tuple[str, Port]],
) -> tuple[CorePort, ...]:
    wanted = [
        f"{name}_t *{name}" if _is_output(pins) else f"{name}_t {name}"
        for name, pins in signatures.items()
    ]
    if len(arguments) != len(signatures) or any(
        a.kind is not ArgumentKind.STRUCT for a in arguments
    ):
        raise RfcError(
            f"HLS top function {top} of accelerator '{accelerator}' has "
            f"{len(arguments)} arguments; taking structs, it needs " + ", ".join(wanted),
            location=arguments[0].location,
            hint=STRUCT_ORDER,
        )
    ports = []
    for argument, (name, pins), want in zip(arguments, signatures.items(), wanted, strict=True):
        output = _is_output(pins)
        if argument.ctype != f"{name}_t" or argument.output != output:
            kind = "pointer to" if argument.output else ""
            raise RfcError(
                f"argument '{argument.name}' of HLS top function {top} is a {kind} "
                f"{argument.ctype}".replace("  ", " ")
                + f"; expected {want}",
                location=argument.location,
                hint=STRUCT_ORDER,
            )
        for port, pin in fields:
            if port == name:
                core = "_".join(str(step) for step in (argument.name, *pin.member))
                ports.append(CorePort(name, pin.name, core, pin.bits, output))
    return tuple(ports)


def _is_output(pins: Sequence[Port]) -> bool:
    """Whether the accelerator sends on the port: its message ``valid`` leaves it."""
    return any(p.role is PortRole.VALID and p.group == ROOT and _output(p) for p in pins)
