"""Loopback: a subscriber wired to a publisher of the same plan, for `rfc msg loopback`.

The ports of the two converters share their names, so the message record connects directly.
Sub-streams and element channels go through FIFOs: the subscriber hands a message's strings,
sequences and elements over while it parses, the publisher takes them only once it has the
message's record (it needs every length to compute the frame length), so the FIFOs hold one
message's worth — sized from the plan's maxima. The entity, ``rfc_loopback``, has fixed ports
(`loopback_ports`) so that one static testbench drives every loopback.
"""

from __future__ import annotations

from math import prod
from typing import Any

from myhdl import ConcatSignal, Signal, always_comb, block, intbv

from rfc.lib.converters.fifo import fifo
from rfc.lib.converters.ports import COUNTER_BITS, Direction, Port, PortRole, Side, ports_of
from rfc.lib.converters.publisher import rfc_publisher
from rfc.lib.converters.steps import ROOT, Loop, Payload, Plan
from rfc.lib.converters.subscriber import rfc_subscriber
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.converters.wiring import follow

#: Entity name of every loopback (the testbench instantiates it by that name).
LOOPBACK = "rfc_loopback"
_DATA = (PortRole.FIELD, PortRole.LENGTH, PortRole.COUNT)


def loopback_ports(width: int) -> tuple[Port, ...]:
    """The loopback's ports: the subscriber's AXI-Stream in, the publisher's out, status."""
    ports = [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
    ]
    for bus, into, out in (
        ("s_axis", Direction.IN, Direction.OUT),
        ("m_axis", Direction.OUT, Direction.IN),
    ):
        ports += [
            Port(f"{bus}_tdata", 8 * width, into, PortRole.TDATA, bus),
            Port(f"{bus}_tkeep", width, into, PortRole.TKEEP, bus),
            Port(f"{bus}_tvalid", 1, into, PortRole.TVALID, bus),
            Port(f"{bus}_tready", 1, out, PortRole.TREADY, bus),
            Port(f"{bus}_tlast", 1, into, PortRole.TLAST, bus),
        ]
    ports += [
        Port("frame_length", COUNTER_BITS, Direction.OUT, PortRole.FRAME_LENGTH),
        Port("error_count", COUNTER_BITS, Direction.OUT, PortRole.ERROR_COUNT),
        Port("fields_valid", 1, Direction.OUT, PortRole.VALID),
    ]
    return tuple(ports)


def _instances(plan: Plan, channel: int) -> int:
    """How many times the steps of a channel can run per message: its loops' maxima."""
    counts = []
    while channel:
        loop = next(s for s in plan.steps if isinstance(s, Loop) and s.element_channel == channel)
        counts.append(loop.maximum)
        channel = loop.channel
    return prod(counts)


@block
def split(word: Any, low: int, target: Any) -> Any:
    """Drive `target` with the bits of `word` from `low` up."""
    high = low + len(target)

    @always_comb
    def extract() -> None:
        target.next = word[high:low]

    return extract


@block
def split_bit(word: Any, low: int, target: Any) -> Any:
    """Drive the single-bit `target` with bit `low` of `word`."""

    @always_comb
    def extract() -> None:
        target.next = word[low]

    return extract


@block
def rfc_loopback(plan: Plan, **ports: Any) -> Any:
    """The subscriber and publisher of `plan`, wired through FIFOs; `ports`: `loopback_ports`."""
    clk, rst = ports["clk"], ports["rst"]
    sub = port_signals(ports_of(plan, Side.SUBSCRIBER))
    pub = port_signals(ports_of(plan, Side.PUBLISHER))
    for port in ports_of(plan, Side.PUBLISHER):
        if port.group == ROOT and port.role in _DATA:
            pub[port.name] = sub[port.name]
    pub["msg_valid"] = sub["msg_valid"]
    sub["msg_ready"] = pub["msg_ready"]
    for name in ("s_axis_tdata", "s_axis_tkeep", "s_axis_tvalid", "s_axis_tready", "s_axis_tlast"):
        sub[name] = ports[name]
    for name in ("m_axis_tdata", "m_axis_tkeep", "m_axis_tvalid", "m_axis_tready", "m_axis_tlast"):
        pub[name] = ports[name]
    sub["error_count"] = ports["error_count"]
    pub["frame_length"] = ports["frame_length"]
    if plan.store_and_forward:
        pub["error_count"] = Signal(intbv(0)[COUNTER_BITS:])  # overflows: none, by sizing
    blocks = [follow(sub["msg_valid"], ports["fields_valid"])]
    for step in plan.steps:
        if isinstance(step, Payload) and step.stream:
            name = step.stream
            beat = len(sub[f"{name}_tdata"]) // 8
            depth = (
                _instances(plan, step.channel) * -(-step.maximum * step.element_size // beat) + 1
            )
            blocks.append(
                fifo(clk, rst, sub[f"{name}_tdata"], sub[f"{name}_tvalid"], sub[f"{name}_tready"],
                     pub[f"{name}_tdata"], pub[f"{name}_tvalid"], pub[f"{name}_tready"], depth)
            )  # fmt: skip
        elif isinstance(step, Loop) and step.count_port:
            name = plan.channels[step.element_channel].name
            data = [
                p.name
                for p in ports_of(plan, Side.SUBSCRIBER)
                if p.group == name and p.role in _DATA
            ]
            # One word per element (a lone bool padded: ConcatSignal needs two parts).
            parts = [sub[p] for p in reversed(data)] or [intbv(0)[1:]]
            word_in = (
                ConcatSignal(intbv(0)[1:], *parts) if len(parts) == 1 else ConcatSignal(*parts)
            )
            word_out = Signal(intbv(0)[len(word_in) :])
            depth = _instances(plan, step.element_channel) + 1
            blocks.append(
                fifo(clk, rst, word_in, sub[f"{name}_valid"], sub[f"{name}_ready"],
                     word_out, pub[f"{name}_valid"], pub[f"{name}_ready"], depth)
            )  # fmt: skip
            low = 0
            for port in data:
                target = pub[port]
                if isinstance(target.val, bool):
                    blocks.append(split_bit(word_out, low, target))
                else:
                    blocks.append(split(word_out, low, target))
                low += len(target)
    blocks.append(rfc_subscriber(plan, clk=clk, rst=rst, **sub))
    blocks.append(rfc_publisher(plan, clk=clk, rst=rst, **pub))
    return blocks
