"""The message signature: the ports of a message on a converter or an accelerator port.

This module is the one contract between the generated blocks and the accelerators: every
generator (converters, wrappers, top level, HLS header, stubs, interface checks) reads the
ports it lists, and no other module spells a port name. Each `Port` carries its flat HDL name
and its *member*: where it sits in the interface object that MyHDL accelerators receive
(``("roi", "x_offset")``, ``("vertex_indices", 2)``, ``("valid",)``).

Conventions (docs/converters.md has the full story):

* a selected fixed-size field is one port named from its path (``header_stamp_sec``,
  ``pose_covariance_35``); it carries the value's bits (two's complement, IEEE 754; a bool is
  one bit);
* a string or primitive sequence ``S`` gives ``S_length`` (characters or elements) and a
  sub-stream ``S_tdata``/``S_tkeep``/``S_tvalid``/``S_tready``/``S_tlast``, a beat holding
  ``max(1, width / element size)`` elements;
* a sequence of messages or strings ``Q`` gives ``Q_length`` (elements) and an element channel:
  the element's ports prefixed ``Q_``, handshake ``Q_valid``/``Q_ready`` (and ``Q_last`` on the
  subscriber); the element of a sequence of strings is its string ``Q_item``: ``Q_item_length``
  and sub-stream ``Q_item``;
* the whole message has the handshake ``msg_valid``/``msg_ready`` (and ``msg_error`` on the
  subscriber).

The publisher has the same names with directions mirrored; it reads neither ``S_tkeep``,
``S_tlast`` nor ``Q_last``, so it does not declare them.

An accelerator port ``p`` has the same ports, mirrored, each prefixed with ``p_``; the message
handshake ``msg_valid``/``msg_ready`` becomes ``p_valid``/``p_ready`` (`accelerator_signature`).
Members use the ROS field names: a field that is a Python keyword gets a trailing underscore
(``from_``), a string or primitive sequence is an object with ``length``, ``data``, ``keep``,
``valid``, ``ready``, ``last``, a sequence of messages an object with ``length``, ``valid``,
``ready``, ``last`` and the element's fields.
"""

from __future__ import annotations

import keyword
from collections.abc import Iterator
from dataclasses import dataclass, replace
from enum import StrEnum

from rfc.errors import RfcError
from rfc.lib.converters.naming import is_identifier
from rfc.lib.converters.steps import ROOT, Loop, Payload, Plan, Record, SlotRole

#: Index of the message's own channel in `Plan.channels`.
ROOT_CHANNEL = 0

#: Bits of the error counter and of the frame-length port.
COUNTER_BITS = 32
#: Bits of the subscriber's ``error_reason`` (`rfc.lib.converters.malformed.Reason`, 0 to 4).
REASON_BITS = 3


class Side(StrEnum):
    """Which converter: the subscriber parses frames, the publisher serializes them."""

    SUBSCRIBER = "subscriber"
    PUBLISHER = "publisher"


class Direction(StrEnum):
    """Port direction as the converter's entity declares it."""

    IN = "in"
    OUT = "out"


class PortRole(StrEnum):
    """What a port carries."""

    CLOCK = "clock"
    RESET = "reset"
    FIELD = "field"
    LENGTH = "length"
    COUNT = "count"
    VALID = "valid"
    READY = "ready"
    LAST = "last"
    ERROR = "error"
    TDATA = "tdata"
    TKEEP = "tkeep"
    TVALID = "tvalid"
    TREADY = "tready"
    TLAST = "tlast"
    ERROR_COUNT = "error_count"
    ERROR_REASON = "error_reason"
    FRAME_LENGTH = "frame_length"


#: Ports that are single wires (std_logic); all others are vectors, even when one bit wide.
WIRES = frozenset(
    {
        PortRole.CLOCK,
        PortRole.RESET,
        PortRole.VALID,
        PortRole.READY,
        PortRole.LAST,
        PortRole.ERROR,
        PortRole.TVALID,
        PortRole.TREADY,
        PortRole.TLAST,
    }
)


@dataclass(frozen=True)
class Port:
    """One port of a generated converter.

    Attributes:
        name: The HDL name.
        bits: Width (1 for single-bit ports, declared as std_logic).
        direction: As the converter declares it.
        role: What it carries.
        group: The handshake it belongs to: ``msg``, an element channel, a sub-stream, or
            ``s_axis``/``m_axis`` on the DMA side; empty for clock, reset and counters.
        path: Field path it carries (``header.stamp.sec``, ``transforms.child_frame_id``), or
            None for handshakes and DMA-side ports.
        ros_type: ROS type of the value (``float64``, ``string``, ``uint8[]``), or None.
        member: Where the port sits in the message's interface object (attribute names and
            list indices), empty for DMA-side ports.
    """

    name: str
    bits: int
    direction: Direction
    role: PortRole
    group: str = ""
    path: str | None = None
    ros_type: str | None = None
    member: tuple[str | int, ...] = ()

    @property
    def is_wire(self) -> bool:
        """Whether the port is a ``std_logic`` (handshakes, clock, reset, bools), else a vector."""
        return self.role in WIRES or self.ros_type == "bool"


def member_text(port: str, member: tuple[str | int, ...]) -> str:
    """How a member is written in Python: ``info.roi.x_offset``, ``tri.vertex_indices[2]``."""
    return port + "".join(f"[{step}]" if isinstance(step, int) else f".{step}" for step in member)


def count_bits(maximum: int) -> int:
    """Bits of a length or count port holding values up to `maximum`."""
    return max(1, maximum.bit_length())


def stream_bytes(payload: Payload, width: int) -> int:
    """Bytes of one sub-stream beat: the bus width, or one element when elements are wider."""
    return max(width, payload.element_size)


def ports_of(plan: Plan, side: Side) -> tuple[Port, ...]:
    """List the accelerator-side ports of the plan's converter, in declaration order."""
    return tuple(_accelerator_ports(plan, side))


def _accelerator_ports(plan: Plan, side: Side) -> Iterator[Port]:
    subscriber = side is Side.SUBSCRIBER
    out, into = (Direction.OUT, Direction.IN) if subscriber else (Direction.IN, Direction.OUT)
    channels = {c.index: c for c in plan.channels}
    # Member prefix of each channel's record: () for the message, the sequence's for elements.
    members: dict[int, tuple[str | int, ...]] = {ROOT_CHANNEL: ()}
    string_elements: set[int] = set()

    def handshake(name: str, member: tuple[str | int, ...], element: bool) -> Iterator[Port]:
        yield Port(f"{name}_valid", 1, out, PortRole.VALID, name, member=(*member, "valid"))
        yield Port(f"{name}_ready", 1, into, PortRole.READY, name, member=(*member, "ready"))
        if subscriber and element:
            yield Port(f"{name}_last", 1, out, PortRole.LAST, name, member=(*member, "last"))
        elif subscriber:
            yield Port(f"{name}_error", 1, out, PortRole.ERROR, name, member=(*member, "error"))

    yield from handshake(ROOT, (), element=False)
    for step in plan.steps:
        if isinstance(step, Record):
            group = channels[step.channel].name
            for slot in step.slots:
                if slot.role is SlotRole.FIELD and slot.port and slot.field:
                    leaf = slot.field
                    bits = 1 if leaf.element_type == "bool" else 8 * slot.size
                    yield Port(
                        slot.port,
                        bits,
                        out,
                        PortRole.FIELD,
                        group,
                        _path(plan, step.channel, leaf.path),
                        leaf.ros_type,
                        (*members[step.channel], *_attributes(leaf.steps)),
                    )
        elif isinstance(step, Payload) and step.stream and step.length_port:
            role = PortRole.LENGTH if step.field.kind.value == "string" else PortRole.COUNT
            group = channels[step.channel].name
            own = ("item",) if step.channel in string_elements else _attributes(step.field.steps)
            member = (*members[step.channel], *own)
            yield Port(
                step.length_port,
                count_bits(step.maximum),
                out,
                role,
                group,
                step.path,
                step.field.ros_type,
                (*member, "length"),
            )
            yield from _stream(step, plan.width, out, into, subscriber, member)
        elif isinstance(step, Loop):
            member = (*members[step.channel], *_attributes(step.field.steps))
            members[step.element_channel] = member
            if step.field.element is None:
                string_elements.add(step.element_channel)
            if not step.count_port:
                continue
            group = channels[step.channel].name
            yield Port(
                step.count_port,
                count_bits(step.maximum),
                out,
                PortRole.COUNT,
                group,
                step.path,
                step.field.ros_type,
                (*member, "length"),
            )
            yield from handshake(channels[step.element_channel].name, member, element=True)


def _attributes(steps: tuple[str | int, ...]) -> tuple[str | int, ...]:
    """Member steps of a field path: Python keywords get a trailing underscore (PEP 8)."""
    return tuple(
        f"{step}_" if isinstance(step, str) and keyword.iskeyword(step) else step for step in steps
    )


def _stream(
    payload: Payload,
    width: int,
    out: Direction,
    into: Direction,
    subscriber: bool,
    member: tuple[str | int, ...],
) -> Iterator[Port]:
    name = payload.stream or ""
    beat = stream_bytes(payload, width)
    path = payload.path

    def port(suffix: str, bits: int, direction: Direction, role: PortRole, attribute: str) -> Port:
        return Port(
            f"{name}_{suffix}", bits, direction, role, name, path, None, (*member, attribute)
        )

    yield port("tdata", 8 * beat, out, PortRole.TDATA, "data")
    if subscriber:
        yield port("tkeep", beat, out, PortRole.TKEEP, "keep")
    yield port("tvalid", 1, out, PortRole.TVALID, "valid")
    yield port("tready", 1, into, PortRole.TREADY, "ready")
    if subscriber:
        yield port("tlast", 1, out, PortRole.TLAST, "last")


def _path(plan: Plan, channel: int, leaf_path: str) -> str:
    """Full path of a leaf: through the sequence whose element holds it."""
    sequence = plan.channels[channel].path
    return f"{sequence}.{leaf_path}" if sequence else leaf_path


def clock_ports() -> list[Port]:
    """Clock and synchronous reset, the first ports of every entity rfc generates."""
    return [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
    ]


def axis_ports(bus: str, width: int, data: Direction) -> list[Port]:
    """The five ports of AXI-Stream `bus` of `width` bytes; `data` is its data's direction."""
    back = Direction.OUT if data is Direction.IN else Direction.IN
    return [
        Port(f"{bus}_tdata", 8 * width, data, PortRole.TDATA, bus),
        Port(f"{bus}_tkeep", width, data, PortRole.TKEEP, bus),
        Port(f"{bus}_tvalid", 1, data, PortRole.TVALID, bus),
        Port(f"{bus}_tready", 1, back, PortRole.TREADY, bus),
        Port(f"{bus}_tlast", 1, data, PortRole.TLAST, bus),
    ]


def stream_path_ports(width: int) -> list[Port]:
    """Clock, reset, a stream in (``s_axis``) and one out (``m_axis``): a block in a path."""
    return [
        *clock_ports(),
        *axis_ports("s_axis", width, Direction.IN),
        *axis_ports("m_axis", width, Direction.OUT),
    ]


def dma_ports(plan: Plan, side: Side) -> tuple[Port, ...]:
    """List clock, reset and the DMA-side ports (AXI-Stream, counters, frame length)."""
    ports = clock_ports()
    if side is Side.SUBSCRIBER:
        ports += axis_ports("s_axis", plan.width, Direction.IN)
    else:
        ports += axis_ports("m_axis", plan.width, Direction.OUT)
    if side is Side.PUBLISHER:
        ports.append(Port("frame_length", COUNTER_BITS, Direction.OUT, PortRole.FRAME_LENGTH))
    if side is Side.SUBSCRIBER or plan.store_and_forward or plan.streamed_last is not None:
        ports.append(Port("error_count", COUNTER_BITS, Direction.OUT, PortRole.ERROR_COUNT))
    if side is Side.SUBSCRIBER:
        ports.append(Port("error_reason", REASON_BITS, Direction.OUT, PortRole.ERROR_REASON))
    return tuple(ports)


def accelerator_port_name(port: str, converter_port: Port) -> str:
    """The accelerator's flat name of a converter-side port.

    ``q`` + ``x`` → ``q_x``; the message's own handshake drops its ``msg`` (``msg_valid`` →
    ``q_valid``).
    """
    if converter_port.group == ROOT and converter_port.role in _MESSAGE_HANDSHAKE:
        return f"{port}_{converter_port.name.removeprefix(f'{ROOT}_')}"
    return f"{port}_{converter_port.name}"


_MESSAGE_HANDSHAKE = frozenset({PortRole.VALID, PortRole.READY, PortRole.ERROR})


def accelerator_signature(plan: Plan, side: Side, port: str) -> tuple[Port, ...]:
    """The ports of accelerator port `port` that a converter of `plan` feeds or is fed by.

    They are the converter's accelerator-side ports mirrored and prefixed with the port's name
    (`accelerator_port_name`); the subscriber's ``msg_error`` stays with the converter, which
    drops malformed frames before an accelerator sees them.

    Args:
        plan: The converter's plan.
        side: The converter: a subscriber feeds an input port, a publisher an output port.
        port: The accelerator's port name.
    """
    mirrored = {Direction.IN: Direction.OUT, Direction.OUT: Direction.IN}
    return tuple(
        replace(p, name=accelerator_port_name(port, p), direction=mirrored[p.direction])
        for p in ports_of(plan, side)
        if not (p.role is PortRole.ERROR and p.group == ROOT)
    )


def check_names(plan: Plan) -> None:
    """Refuse port names that are not HDL identifiers or that two fields share.

    Raises:
        RfcError: Naming the field (or both fields) and suggesting to exclude one.
    """
    seen: dict[str, str] = {}
    ports = [*dma_ports(plan, Side.SUBSCRIBER), *dma_ports(plan, Side.PUBLISHER)]
    for port in (*ports, *ports_of(plan, Side.SUBSCRIBER)):
        what = port.path or f"the converter's own '{port.name}'"
        if not is_identifier(port.name):
            raise RfcError(
                f"field '{port.path}' of {plan.layout.display_name} gives the port name "
                f"'{port.name}', which is not a valid VHDL identifier",
                hint=f"exclude '{port.path}' or rename the field",
            )
        key = port.name.lower()
        if key in seen and seen[key] != what:
            first = seen[key]
            raise RfcError(
                f"{_describe(first)} and {_describe(what)} of {plan.layout.display_name} "
                f"would both use the port name '{port.name}'",
                hint=f"exclude '{port.path or first}'",
            )
        seen.setdefault(key, what)
    _check_members(plan)


def _check_members(plan: Plan) -> None:
    """Refuse fields whose interface-object member is a handshake's (``valid``, ``length`` ...)."""
    owners: dict[tuple[str | int, ...], Port] = {}
    for port in ports_of(plan, Side.SUBSCRIBER):
        other = owners.setdefault(port.member, port)
        if other is port:
            continue
        field, handshake = (port, other) if port.role is PortRole.FIELD else (other, port)
        attribute = ".".join(str(step) for step in port.member)
        raise RfcError(
            f"field '{field.path}' of {plan.layout.display_name} would be the member "
            f"'{attribute}' of the accelerator's interface object, which is "
            f"{_role(handshake)}",
            hint=f"exclude '{field.path}' from the accelerator's port",
        )


def _role(port: Port) -> str:
    if port.role is PortRole.FIELD:
        return f"field '{port.path}'"
    return f"the {port.role.value} of the {'message' if port.group == ROOT else port.group}"


def _describe(what: str) -> str:
    return what if what.startswith("the converter") else f"field '{what}'"
