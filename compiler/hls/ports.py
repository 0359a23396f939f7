"""How an HLS top function's arguments become the data ports of its Vitis HLS core.

Two forms of top function reach the logic (docs/accelerators.md, "HLS accelerators"):

* scalar arguments, one per selected field: the core's port is named like the argument;
* one message struct per port (`rfc.hls.c_types`), inputs by value and outputs by pointer,
  each followed by one ``hls::stream`` per string or primitive sequence of the port. The Vitis
  HLS run disaggregates each struct and completely partitions each of its arrays
  (`vitis_directives`), so that every scalar member becomes one port named
  ``<argument>_<member>`` (``state_O_T_EE_15``, ``rgb_data_length``) — the name the message
  signature gives the same field, with the argument's name in front; a stream is an ``ap_fifo``
  named like its argument.

Inputs are ``ap_none`` ports, outputs ``<name>`` with ``<name>_ap_vld``: the ap_ctrl wrapper
(`rfc.lib.hls.adapter`) keeps the inputs steady from ``ap_start`` to ``ap_done`` and captures
each output when its ``_ap_vld`` pulses. The wrapper starts the core at the first beat of an
input port's last stream, before the subscriber has the rest of the frame, and holds the port's
earlier streams whole in FIFOs (`held_streams`) so that the subscriber can go on to it; so the
fields an input port selects must come before its last stream (`core_ports` refuses other
ports). Sequences of messages or strings and bool fields are not wired.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from rfc.errors import RfcError
from rfc.hls.c_types import message_struct
from rfc.hls.signature import SCALAR_BITS, ArgumentKind, HlsArgument, read_top_function
from rfc.ir.model import AcceleratorType, Block
from rfc.lib.converters.buffer_sizes import Buffer
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import ROOT_CHANNEL, Direction, Port, PortRole, stream_bytes
from rfc.lib.converters.steps import ROOT, Payload, Plan
from rfc.messages.limits import Limits

#: Bits of a stream's length in the core (``uint32_t``).
LENGTH_BITS = 32
#: A sub-stream's pins besides its data: carried with the stream.
_STREAM_ROLES = frozenset(
    {PortRole.TDATA, PortRole.TKEEP, PortRole.TVALID, PortRole.TREADY, PortRole.TLAST}
)
#: What a struct member carries: a field, or the length of a string or sequence.
_STRUCT_ROLES = frozenset({PortRole.FIELD, PortRole.LENGTH, PortRole.COUNT})
#: How the scalar form orders its arguments.
SCALAR_ORDER = "inputs' fields by value, then outputs' fields by pointer (docs/accelerators.md)"
#: How the struct form orders its arguments.
STRUCT_ORDER = (
    "per port in the spec's order, its struct (inputs by value, outputs by pointer) and then "
    "one hls::stream per string or sequence, as "
    "<accelerator>_messages.h declares the function (`rfc stub SPEC ACCELERATOR --lang hls`)"
)


@dataclass(frozen=True)
class CorePort:
    """One data port of the Vitis core and the message field it carries.

    Attributes:
        message_port: The accelerator's port the field belongs to.
        field: The field's pin in the message signature (``state_q_0``).
        core: The core's port (``state_q_0``; a scalar argument's name).
        bits: The field's width.
        output: The core drives it (with ``<core>_ap_vld``).
        core_bits: The core port's width: a stream's length is a ``uint32_t``.
    """

    message_port: str
    field: str
    core: str
    bits: int
    output: bool
    core_bits: int

    @property
    def length(self) -> bool:
        """Whether it is a stream's length (as wide in the core as a ``uint32_t``)."""
        return self.core_bits != self.bits


@dataclass(frozen=True)
class CoreStream:
    """One ``hls::stream`` argument of the core and the sub-stream it carries.

    Attributes:
        message_port: The accelerator's port the stream belongs to.
        path: The string's or sequence's field path (``header.frame_id``).
        stream: Prefix of the sub-stream's pins in the message signature (``rgb_data``).
        core: The argument's name: prefix of the core's ``ap_fifo`` ports.
        element: Bits of one element.
        beat: Bits of a beat of the sub-stream.
        output: The core writes it.
    """

    message_port: str
    path: str
    stream: str
    core: str
    element: int
    beat: int
    output: bool


@dataclass(frozen=True)
class CoreInterface:
    """The core's data ports: fields and lengths, then streams."""

    ports: tuple[CorePort, ...]
    streams: tuple[CoreStream, ...] = ()


def accelerator_core(
    accelerator: AcceleratorType, signatures: Mapping[str, Sequence[Port]]
) -> tuple[tuple[HlsArgument, ...], CoreInterface]:
    """Read an HLS accelerator's top function and match it with its ports' signatures.

    It needs only the accelerator and its signatures, which check-hardware has too.

    Raises:
        RfcError: As `core_ports`, at the argument or else at the accelerator.
    """
    top = accelerator.top or accelerator.name
    arguments = read_top_function(list(accelerator.sources), top)
    try:
        return arguments, core_ports(accelerator.name, top, arguments, signatures)
    except RfcError as exc:
        if exc.location is not None:
            raise
        raise RfcError(exc.message, location=accelerator.location, hint=exc.hint) from None


def core_ports(
    accelerator: str,
    top: str,
    arguments: Sequence[HlsArgument],
    signatures: Mapping[str, Sequence[Port]],
) -> CoreInterface:
    """Match the top function's arguments with the message fields, port by port.

    Args:
        accelerator: The accelerator type's name (for messages).
        top: The top function's name.
        arguments: Its arguments (`rfc.hls.signature.read_top_function`).
        signatures: Per accelerator port, in the spec's order (inputs, then outputs), its
            message signature.

    Raises:
        RfcError: An argument that does not match its field, struct or stream; a field the
            logic does not wire; an input stream before a field the core reads.
    """
    if any(a.kind is not ArgumentKind.SCALAR for a in arguments):
        return _struct_ports(accelerator, top, arguments, signatures)
    fields = [(port, pin) for port, pins in signatures.items() for pin in _fields(port, pins)]
    return CoreInterface(_scalar_ports(accelerator, top, arguments, fields))


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
        if argument.kind is ArgumentKind.STREAM:
            mode = "ap_fifo"
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


def _wrong_argument(
    argument: HlsArgument, top: str, found: str, expected: str, hint: str
) -> RfcError:
    """The refusal of one argument of the top function: what it is, what its port needs."""
    return RfcError(
        f"argument '{argument.name}' of HLS top function {top} is {found}; expected {expected}",
        location=argument.location,
        hint=hint,
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
            raise _wrong_argument(
                argument, top, f"a {argument.bits}-bit {kind}", f"a {want}", SCALAR_ORDER
            )
        core = CorePort(port, pin.name, argument.name, pin.bits, argument.output, pin.bits)
        ports.append(core)
    return tuple(ports)


def _struct_ports(
    accelerator: str,
    top: str,
    arguments: Sequence[HlsArgument],
    signatures: Mapping[str, Sequence[Port]],
) -> CoreInterface:
    structs = {
        name: message_struct(name, tuple(pins), _is_output(pins))
        for name, pins in signatures.items()
    }
    wanted = [a for struct in structs.values() for a in struct.arguments()]
    kinds = [
        k
        for s in structs.values()
        for k in (ArgumentKind.STRUCT, *[ArgumentKind.STREAM] * len(s.streams))
    ]
    if [a.kind for a in arguments] != kinds:
        raise RfcError(
            f"HLS top function {top} of accelerator '{accelerator}' has {len(arguments)} "
            f"arguments; taking structs, it needs {len(wanted)}: " + ", ".join(wanted),
            location=arguments[0].location,
            hint=STRUCT_ORDER,
        )
    ports: list[CorePort] = []
    streams: list[CoreStream] = []
    remaining = list(arguments)
    for name, struct in structs.items():
        argument = remaining.pop(0)
        want = struct.arguments()[0]
        # The struct form's own check (C type and pointer), not the scalar form's (bits and
        # direction): the two refusals name what each form gets wrong.
        if argument.ctype != struct.type_name or argument.output != struct.output:
            kind = "pointer to " if argument.output else ""
            raise _wrong_argument(argument, top, f"a {kind}{argument.ctype}", want, STRUCT_ORDER)
        pins = signatures[name]
        ports += _struct_fields(name, argument, pins)
        for stream, want in zip(struct.streams, struct.arguments()[1:], strict=True):
            argument = remaining.pop(0)
            if argument.ctype != f"hls::stream<{stream.element}>":
                raise _wrong_argument(
                    argument,
                    top,
                    f"a {argument.ctype}",
                    f"{want} for '{stream.path}'",
                    STRUCT_ORDER,
                )
            tdata = next(p for p in pins if p.role is PortRole.TDATA and p.path == stream.path)
            streams.append(
                CoreStream(
                    name,
                    stream.path,
                    tdata.name.removesuffix("_tdata"),
                    argument.name,
                    SCALAR_BITS[stream.element],
                    tdata.bits,
                    struct.output,
                )
            )
        if not struct.output:
            _check_order(name, pins)
    return CoreInterface(tuple(ports), tuple(streams))


def _struct_fields(name: str, argument: HlsArgument, pins: Sequence[Port]) -> list[CorePort]:
    """The struct's members as core ports: fields and stream lengths."""
    ports = []
    output = _is_output(pins)
    for pin in _members(name, pins):
        core = "_".join(str(step) for step in (argument.name, *pin.member))
        bits = pin.bits if pin.role is PortRole.FIELD else LENGTH_BITS
        ports.append(CorePort(name, pin.name, core, pin.bits, output, bits))
    return ports


def _members(name: str, pins: Sequence[Port]) -> list[Port]:
    """The struct's members among a port's pins; what the logic does not wire refused."""
    members = []
    for pin in pins:
        if pin.group == ROOT and pin.role in (PortRole.VALID, PortRole.READY):
            continue
        if pin.role in _STREAM_ROLES and pin.group != ROOT:
            continue
        if pin.group != ROOT or pin.role not in _STRUCT_ROLES:
            raise _refusal(name, pin, "a sequence of messages or of strings")
        if pin.is_wire:
            raise _refusal(name, pin, "a bool")
        members.append(pin)
    return members


def logic_refusal(name: str, pins: Sequence[Port]) -> RfcError | None:
    """Why a port in the struct form cannot reach a core in the logic, or None if it can.

    `rfc stub` says so in the skeleton: the function C-simulates all the same.
    """
    try:
        _members(name, pins)
        if not _is_output(pins):
            _check_order(name, pins)
    except RfcError as exc:
        return exc
    return None


def _check_order(name: str, pins: Sequence[Port]) -> None:
    """Refuse an input port that selects a field after its last stream.

    Raises:
        RfcError: Naming the last stream and the first field after it.
    """
    streams = [p for p in pins if p.role is PortRole.TDATA]
    if not streams:
        return
    after = pins[pins.index(streams[-1]) :]
    late = next(
        (p for p in after if p.group == ROOT and p.role in _STRUCT_ROLES),
        None,
    )
    if late is not None:
        field = (late.path or late.name).split("[")[0]  # an array's element: the array
        raise RfcError(
            f"port '{name}' selects '{late.path}' after its last string or sequence "
            f"'{streams[-1].path}': an HLS core in the logic starts at that stream's first "
            f"element, before the subscriber has '{late.path}'",
            hint=f"exclude '{field}' or '{streams[-1].path}' from port '{name}' (the fields of "
            "an input port must come before its last string or sequence)",
        )


def input_holds(block: Block, width: int, limits: Limits) -> tuple[tuple[str, Buffer], ...]:
    """The FIFOs of an HLS accelerator block's wrapper, each with its input port's name."""
    return tuple(
        (port.name, buffer)
        for port in block.inputs
        if port.layout is not None
        for buffer in held_streams(plan(port.layout, width, limits))
    )


def held_streams(chosen: Plan) -> tuple[Buffer, ...]:
    """The FIFOs of an HLS core's input port: one per string or sequence but its last.

    The subscriber sends those streams before the one whose first beat starts the core, so the
    wrapper holds each whole, up to its maximum (strings ``maxima.string``), in beats with
    their ``tkeep``.

    Args:
        chosen: The plan of the subscriber feeding the port.
    """
    payloads = [
        s
        for s in chosen.steps
        if isinstance(s, Payload) and s.stream is not None and s.channel == ROOT_CHANNEL
    ]
    held = []
    for payload in payloads[:-1]:
        assert payload.stream is not None
        beat = stream_bytes(payload, chosen.width)
        words = -(-payload.maximum * payload.element_size // beat)
        held.append(Buffer(payload.stream, payload.path, words, beat * 8 + beat))
    return tuple(held)


def _is_output(pins: Sequence[Port]) -> bool:
    """Whether the accelerator sends on the port: its message ``valid`` leaves it."""
    return any(p.role is PortRole.VALID and p.group == ROOT and _output(p) for p in pins)
