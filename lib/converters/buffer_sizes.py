"""How much a publisher's buffers hold: one message's strings, sequences and elements.

Apart from the MyHDL blocks that build them (`rfc.lib.converters.buffers`), so that checking a
spec's block RAM (`rfc check`) does not import MyHDL.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import prod

from rfc.lib.converters.ports import Port, PortRole, Side, ports_of
from rfc.lib.converters.steps import Loop, Payload, Plan

#: The roles of the ports that carry data (not handshakes).
DATA_ROLES = (PortRole.FIELD, PortRole.LENGTH, PortRole.COUNT)


@dataclass(frozen=True)
class Buffer:
    """One FIFO in front of a publisher (or the whole-frame buffer of a subscriber's guard).

    Attributes:
        channel: The sub-stream or element channel it holds.
        path: The field's dotted path, as the project's maxima name it.
        words: Its memory's depth: one message's worth (the FIFO's output register holds one
            more).
        bits: Bits per word.
    """

    channel: str
    path: str
    words: int
    bits: int

    @property
    def size_bits(self) -> int:
        """Its memory in bits."""
        return self.words * self.bits


def buffers_of(plan: Plan) -> tuple[Buffer, ...]:
    """The FIFOs a publisher of `plan` needs (none when it takes no strings or sequences)."""
    ports = ports_of(plan, Side.PUBLISHER)
    # the channels of sequences of strings: each string's maximum is keyed ``path[]``
    string_loops = {
        s.element_channel for s in plan.steps if isinstance(s, Loop) and s.field.element is None
    }
    found = []
    through = plan.streamed_last
    for at, step in enumerate(plan.steps):
        if at == through:
            continue  # a record-first producer's last stream goes straight through
        if isinstance(step, Payload) and step.stream:
            bits = next(p.bits for p in ports if p.name == f"{step.stream}_tdata")
            beats = -(-step.maximum * step.element_size // (bits // 8))
            path = step.path + ("[]" if step.channel in string_loops else "")
            found.append(Buffer(step.stream, path, _instances(plan, step.channel) * beats, bits))
        elif isinstance(step, Loop) and step.count_port:
            name = plan.channels[step.element_channel].name
            bits = _word_bits([p.bits for p in element_ports(ports, name)])
            count = _instances(plan, step.element_channel)
            found.append(Buffer(name, step.path, count, bits))
    return tuple(found)


def _instances(plan: Plan, channel: int) -> int:
    """How many times the steps of a channel can run per message: its loops' maxima."""
    counts = []
    while channel:
        loop = next(s for s in plan.steps if isinstance(s, Loop) and s.element_channel == channel)
        counts.append(loop.maximum)
        channel = loop.channel
    return prod(counts)


def element_ports(ports: tuple[Port, ...], channel: str) -> list[Port]:
    """The data ports of one element channel, in the order a FIFO word packs them."""
    return [p for p in ports if p.group == channel and p.role in DATA_ROLES]


def _word_bits(parts: list[int]) -> int:
    """Bits of the FIFO word of an element channel, as `stream_buffers` packs it."""
    parts = parts or [1]  # no data: a constant bit
    return sum(parts) + (1 if len(parts) == 1 else 0)  # one part: padded, see below
