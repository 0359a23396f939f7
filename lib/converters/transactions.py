"""What crosses a converter's accelerator side for one message, as plain Python values.

A subscriber presents, and a publisher takes, per message: one record on the message channel
(field ports and length/count ports, as unsigned integers), the contents of each sub-stream
(one byte string per string or sequence instance), and one record per element on each element
channel. `transactions` computes them from the codec's flat values; `values_of` goes back.
Test benches drive and check converters with them; software that stands in for an accelerator
can use them too.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rfc.lib.converters.steps import Loop, Payload, Plan, Record, SlotRole
from rfc.messages.codec import PRIMITIVE_STRUCTS, Values, default_values
from rfc.messages.layout import FieldKind, Layout, LayoutField
from rfc.messages.rosbags_adapter import PRIMITIVE_DTYPES


@dataclass
class Transactions:
    """One message as the accelerator side sees it.

    Attributes:
        record: Port name → value of the message channel (fields, lengths, counts).
        streams: Sub-stream name → the bytes of each of its instances, in frame order.
        elements: Element channel name → one record per element, in frame order.
    """

    record: dict[str, int] = field(default_factory=dict)
    streams: dict[str, list[bytes]] = field(default_factory=dict)
    elements: dict[str, list[dict[str, int]]] = field(default_factory=dict)


def port_value(ros_type: str, value: Any) -> int:
    """The unsigned integer a field port carries for a value (floats as IEEE 754 bits)."""
    if ros_type == "bool":
        return int(bool(value))
    return int.from_bytes(PRIMITIVE_STRUCTS[ros_type].pack(value), "little")


def field_value(ros_type: str, bits: int) -> Any:
    """The value a field port's unsigned integer stands for (inverse of `port_value`)."""
    if ros_type == "bool":
        return bool(bits)
    packing = PRIMITIVE_STRUCTS[ros_type]
    return packing.unpack(bits.to_bytes(packing.size, "little"))[0]


def transactions(plan: Plan, values: Mapping[str, Any]) -> Transactions:
    """What the plan's converters present or take for a message with these flat values.

    Fields the plan does not select are ignored; a publisher sends their defaults.
    """
    result = Transactions()
    _walk(plan, 0, len(plan.steps), values, result.record, result)
    return result


def _walk(plan: Plan, start: int, stop: int, values: Mapping[str, Any], record: dict[str, int],
          result: Transactions) -> None:  # fmt: skip
    at = start
    while at < stop:
        step = plan.steps[at]
        if isinstance(step, Record):
            for port, leaf in _selected(step):
                record[port] = port_value(leaf.element_type, values[leaf.path])
        elif isinstance(step, Payload):
            data = _payload_bytes(step, values[step.field.path])
            if step.stream and step.length_port:
                record[step.length_port] = len(data) // step.element_size
                result.streams.setdefault(step.stream, []).append(data)
        elif isinstance(step, Loop):
            items = values[step.field.path]
            channel = plan.channels[step.element_channel]
            if step.count_port:
                record[step.count_port] = len(items)
            for item in items:
                element: dict[str, int] = {}
                scope = item if isinstance(item, Mapping) else {step.field.path: item}
                _walk(plan, at + 1, step.next, scope, element, result)
                if channel.selected:
                    result.elements.setdefault(channel.name, []).append(element)
            at = step.next
        at += 1


def _selected(record: Record) -> Iterator[tuple[str, LayoutField]]:
    """The port and leaf of each field of `record` the accelerator sees."""
    for slot in record.slots:
        if slot.role is SlotRole.FIELD and slot.port and slot.field:
            yield slot.port, slot.field


def _payload_bytes(step: Payload, value: Any) -> bytes:
    if step.field.kind is FieldKind.STRING:
        text: str = value
        return text.encode()
    array = np.asarray(value, dtype=PRIMITIVE_DTYPES[step.field.element_type])
    if step.is_bool:
        array = array.astype(bool).astype(np.uint8)
    return array.tobytes()


def values_of(plan: Plan, message: Transactions) -> Values:
    """Flat values of a message from what crossed the accelerator side.

    Fields the plan does not select get their defaults, as a publisher sends them.
    """
    streams = {name: list(items) for name, items in message.streams.items()}
    elements = {name: list(items) for name, items in message.elements.items()}
    return _unwalk(plan, plan.layout, 0, len(plan.steps), message.record, streams, elements)


def _unwalk(plan: Plan, layout: Layout, start: int, stop: int, record: Mapping[str, int],
            streams: dict[str, list[bytes]], elements: dict[str, list[dict[str, int]]]
            ) -> Values:  # fmt: skip
    values = default_values(layout)
    at = start
    while at < stop:
        step = plan.steps[at]
        if isinstance(step, Record):
            for port, leaf in _selected(step):
                values[leaf.path] = field_value(leaf.element_type, record[port])
        elif isinstance(step, Payload) and step.stream:
            data = streams[step.stream].pop(0)
            if step.field.kind is FieldKind.STRING:
                values[step.field.path] = data.decode(errors="surrogateescape")
            else:
                dtype = PRIMITIVE_DTYPES[step.field.element_type]
                values[step.field.path] = np.frombuffer(data, dtype=np.uint8).view(dtype).copy()
        elif isinstance(step, Loop):
            count = record[step.count_port] if step.count_port else 0
            channel = plan.channels[step.element_channel]
            items: list[Values | str] = []
            for _ in range(count):
                element = elements[channel.name].pop(0)
                inner = step.field.element
                if inner is not None:
                    items.append(_unwalk(plan, inner, at + 1, step.next, element, streams,
                                         elements))  # fmt: skip
                else:  # a sequence of strings: the element is its string
                    string = plan.steps[step.next - 1]
                    assert isinstance(string, Payload)
                    assert string.stream
                    items.append(streams[string.stream].pop(0).decode(errors="surrogateescape"))
            values[step.field.path] = items
            at = step.next
        at += 1
    return values
