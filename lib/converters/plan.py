"""Compile a selected message layout into the `Plan` a converter executes (see `steps`)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from rfc.errors import RfcError
from rfc.lib.converters.naming import port_name, safe_name
from rfc.lib.converters.ports import Port, Side, check_names, ports_of
from rfc.lib.converters.steps import (
    ROOT,
    Channel,
    End,
    Loop,
    Next,
    Payload,
    Plan,
    Record,
    Slot,
    SlotRole,
    Step,
)
from rfc.messages.layout import LENGTH_PREFIX_SIZE, FieldKind, Layout, LayoutField
from rfc.messages.limits import Limits

#: Bus widths in bits a converter supports on its AXI-Stream side.
BUS_WIDTHS = (8, 32, 64)


def plan(layout: Layout, width: int, limits: Limits | None = None) -> Plan:
    """Compile a selected layout for a bus width.

    Args:
        layout: From `rfc.messages.layout.flatten`, optionally through `select`.
        width: Bus width in bits: 8, 32 or 64.
        limits: Maxima for unbounded strings and sequences; defaults when omitted.

    Returns:
        The plan.

    Raises:
        RfcError: The width is not supported, the message has no fields, or a selected field's
            port name is not a valid HDL identifier or collides with another port.
    """
    if width not in BUS_WIDTHS:
        raise RfcError(
            f"bus width {width} is not supported; expected one of "
            f"{', '.join(map(str, BUS_WIDTHS))} bits"
        )
    if not layout.fields:
        raise RfcError(
            f"{layout.display_name} has no fields on the {layout.middleware.label} wire: "
            "there is nothing to convert",
            hint="send a message type with at least one field",
        )
    builder = _Builder(layout, limits or Limits())
    builder.walk(layout, channel=0, prefix="", path_prefix="")
    builder.close()
    builder.steps.append(End())
    result = Plan(layout, width // 8, builder.limits, tuple(builder.steps), tuple(builder.channels))
    check_names(result)
    return result


def accelerator_ports(
    layout: Layout, width: int, side: Side = Side.SUBSCRIBER, limits: Limits | None = None
) -> tuple[Port, ...]:
    """List the accelerator-side ports of a converter, as the generated entity declares them.

    Subscriber and publisher of the same layout use the same names (directions mirrored), so
    one can be wired to the other, and an accelerator can be written against either.

    Args:
        layout: The flattened, selected layout.
        width: Bus width in bits.
        side: Which converter.
        limits: Configured maxima (they decide the widths of length and count ports).

    Raises:
        RfcError: As `plan` does.
    """
    return ports_of(plan(layout, width, limits), side)


@dataclass
class _OpenRecord:
    """A record being filled: slots are placed at aligned offsets as they come."""

    align: int
    skew: int  # how far the record's first byte is from an 8-byte boundary of the CDR payload
    channel: int
    size: int = 0
    slots: list[Slot] = field(default_factory=list)

    def place(self, align: int, slot: Slot) -> None:
        offset = -(-(self.size + self.skew) // align) * align - self.skew
        self.size = offset + slot.size
        self.slots.append(replace(slot, offset=offset))


class _Builder:
    """Walks a layout depth first, cutting records where run-time lengths intervene."""

    def __init__(self, layout: Layout, limits: Limits) -> None:
        self.cdr = layout.is_cdr
        self.limits = limits
        self.steps: list[Step] = []
        self.channels = [Channel(0, ROOT, "", None, True)]
        # The first record starts at the frame's first byte: static until the first payload.
        self.record: _OpenRecord | None = _OpenRecord(1, layout.header_size, 0)
        if layout.header_size:
            self.record.place(1, Slot(0, layout.header_size, SlotRole.ENCAPSULATION))
        self.static = True

    def walk(self, layout: Layout, channel: int, prefix: str, path_prefix: str) -> None:
        for leaf in layout.fields:
            path = path_prefix + leaf.path
            name = safe_name(port_name(leaf.steps, prefix))
            if leaf.kind is FieldKind.PRIMITIVE:
                port = name if leaf.selected else None
                slot = Slot(0, leaf.element_size or 0, SlotRole.FIELD, leaf, port)
                self.place(leaf.align, slot, channel)
                continue
            prefix_slot = Slot(0, LENGTH_PREFIX_SIZE, SlotRole.LENGTH, leaf)
            self.place(leaf.align, prefix_slot, channel)
            self.close()
            maximum = self.limits.maximum(leaf, path)
            if leaf.kind is FieldKind.STRING or (
                leaf.element is None and leaf.element_type != "string"
            ):
                self.payload(leaf, path, channel, maximum, name)
            else:
                self.loop(leaf, path, channel, maximum, name)

    def payload(self, leaf: LayoutField, path: str, channel: int, maximum: int, name: str) -> None:
        size = 1 if leaf.kind is FieldKind.STRING else leaf.element_size or 1
        # The length prefix is 4-aligned: only 8-byte elements may need padding after it.
        align = 8 if self.cdr and size == 8 else 1
        terminator = self.cdr and leaf.kind is FieldKind.STRING
        chosen = leaf.selected
        self.steps.append(
            Payload(
                leaf,
                path,
                channel,
                size,
                align,
                terminator,
                maximum,
                name if chosen else None,
                f"{name}_length" if chosen else None,
            )
        )

    def loop(self, leaf: LayoutField, path: str, channel: int, maximum: int, name: str) -> None:
        element_channel = len(self.channels)
        self.channels.append(Channel(element_channel, name, path, channel, leaf.selected))
        start = len(self.steps)
        count_port = f"{name}_length" if leaf.selected else None
        loop = Loop(leaf, path, channel, element_channel, maximum, count_port, -1)
        self.steps.append(loop)
        if leaf.element is not None:
            self.walk(leaf.element, element_channel, name + "_", path + ".")
        else:
            self.string_element(leaf, path, element_channel, name)
        self.close()
        self.steps.append(Next(start, element_channel))
        self.steps[start] = replace(loop, next=len(self.steps) - 1)

    def string_element(self, leaf: LayoutField, path: str, channel: int, name: str) -> None:
        """One string of a sequence of strings: its length prefix, then its characters."""
        string = LayoutField(
            leaf.steps,
            "string",
            FieldKind.STRING,
            "string",
            leaf.align,
            None,
            bound=leaf.string_bound,
            selected=leaf.selected,
        )
        self.place(string.align, Slot(0, LENGTH_PREFIX_SIZE, SlotRole.LENGTH, string), channel)
        self.close()
        maximum = self.limits.string_in_sequence(leaf, path)
        self.payload(string, path, channel, maximum, f"{name}_item")

    def place(self, align: int, slot: Slot, channel: int) -> None:
        align = align if self.cdr else 1
        if self.record is None or (not self.static and align > self.record.align):
            self.close()
            self.record = _OpenRecord(align, 0, channel)
        self.record.place(align, slot)

    def close(self) -> None:
        record = self.record
        if record is not None and record.slots:
            self.steps.append(
                Record(record.align, record.size, tuple(record.slots), record.channel)
            )
        self.record = None
        self.static = False
