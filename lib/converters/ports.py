"""The ports of a converter: accelerator side (named from field paths) and DMA side.

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
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from enum import StrEnum

from rfc.errors import RfcError
from rfc.lib.converters.naming import is_identifier
from rfc.lib.converters.steps import ROOT, Loop, Payload, Plan, Record, SlotRole

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
    """

    name: str
    bits: int
    direction: Direction
    role: PortRole
    group: str = ""
    path: str | None = None
    ros_type: str | None = None


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

    def handshake(name: str, element: bool) -> Iterator[Port]:
        yield Port(f"{name}_valid", 1, out, PortRole.VALID, name)
        yield Port(f"{name}_ready", 1, into, PortRole.READY, name)
        if subscriber and element:
            yield Port(f"{name}_last", 1, out, PortRole.LAST, name)
        elif subscriber:
            yield Port(f"{name}_error", 1, out, PortRole.ERROR, name)

    yield from handshake(ROOT, element=False)
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
                    )
        elif isinstance(step, Payload) and step.stream and step.length_port:
            role = PortRole.LENGTH if step.field.kind.value == "string" else PortRole.COUNT
            group = channels[step.channel].name
            yield Port(
                step.length_port,
                count_bits(step.maximum),
                out,
                role,
                group,
                step.path,
                step.field.ros_type,
            )
            yield from _stream(step, plan.width, out, into, subscriber)
        elif isinstance(step, Loop) and step.count_port:
            group = channels[step.channel].name
            yield Port(
                step.count_port,
                count_bits(step.maximum),
                out,
                PortRole.COUNT,
                group,
                step.path,
                step.field.ros_type,
            )
            yield from handshake(channels[step.element_channel].name, element=True)


def _stream(
    payload: Payload, width: int, out: Direction, into: Direction, subscriber: bool
) -> Iterator[Port]:
    name = payload.stream or ""
    beat = stream_bytes(payload, width)
    yield Port(f"{name}_tdata", 8 * beat, out, PortRole.TDATA, name, payload.path)
    if subscriber:
        yield Port(f"{name}_tkeep", beat, out, PortRole.TKEEP, name, payload.path)
    yield Port(f"{name}_tvalid", 1, out, PortRole.TVALID, name, payload.path)
    yield Port(f"{name}_tready", 1, into, PortRole.TREADY, name, payload.path)
    if subscriber:
        yield Port(f"{name}_tlast", 1, out, PortRole.TLAST, name, payload.path)


def _path(plan: Plan, channel: int, leaf_path: str) -> str:
    """Full path of a leaf: through the sequence whose element holds it."""
    sequence = plan.channels[channel].path
    return f"{sequence}.{leaf_path}" if sequence else leaf_path


def dma_ports(plan: Plan, side: Side) -> tuple[Port, ...]:
    """List clock, reset and the DMA-side ports (AXI-Stream, counters, frame length)."""
    width = plan.width
    ports = [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
    ]
    if side is Side.SUBSCRIBER:
        bus, out, into = "s_axis", Direction.IN, Direction.OUT
    else:
        bus, out, into = "m_axis", Direction.OUT, Direction.IN
    ports += [
        Port(f"{bus}_tdata", 8 * width, out, PortRole.TDATA, bus),
        Port(f"{bus}_tkeep", width, out, PortRole.TKEEP, bus),
        Port(f"{bus}_tvalid", 1, out, PortRole.TVALID, bus),
        Port(f"{bus}_tready", 1, into, PortRole.TREADY, bus),
        Port(f"{bus}_tlast", 1, out, PortRole.TLAST, bus),
    ]
    if side is Side.PUBLISHER:
        ports.append(Port("frame_length", COUNTER_BITS, Direction.OUT, PortRole.FRAME_LENGTH))
    if side is Side.SUBSCRIBER or plan.store_and_forward:
        ports.append(Port("error_count", COUNTER_BITS, Direction.OUT, PortRole.ERROR_COUNT))
    if side is Side.SUBSCRIBER:
        ports.append(Port("error_reason", REASON_BITS, Direction.OUT, PortRole.ERROR_REASON))
    return tuple(ports)


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


def _describe(what: str) -> str:
    return what if what.startswith("the converter") else f"field '{what}'"
