"""Loopback: a subscriber wired to a publisher of the same plan, for `rfc msg loopback`.

The ports of the two converters share their names, so the message record connects directly.
Sub-streams and element channels go through the publisher's buffers
(`rfc.lib.converters.buffers`): the subscriber hands a message's strings, sequences and
elements over while it parses, before its record. The entity, ``rfc_loopback``, has fixed ports
(`loopback_ports`) so that one static testbench drives every loopback.
"""

from __future__ import annotations

from myhdl import Signal, block, intbv

from rfc.lib.converters.buffers import DATA_ROLES, stream_buffers
from rfc.lib.converters.ports import (
    COUNTER_BITS,
    REASON_BITS,
    Direction,
    Port,
    PortRole,
    Side,
    ports_of,
    stream_path_ports,
)
from rfc.lib.converters.publisher import rfc_publisher
from rfc.lib.converters.steps import ROOT, Plan
from rfc.lib.converters.subscriber import rfc_subscriber
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.converters.wiring import follow
from rfc.lib.types import Instances, SignalLike

#: Entity name of every loopback (the testbench instantiates it by that name).
LOOPBACK = "rfc_loopback"


def loopback_ports(width: int) -> tuple[Port, ...]:
    """The loopback's ports: the subscriber's AXI-Stream in, the publisher's out, status."""
    return (
        *stream_path_ports(width),
        Port("frame_length", COUNTER_BITS, Direction.OUT, PortRole.FRAME_LENGTH),
        Port("error_count", COUNTER_BITS, Direction.OUT, PortRole.ERROR_COUNT),
        Port("fields_valid", 1, Direction.OUT, PortRole.VALID),
    )


@block
def rfc_loopback(plan: Plan, **ports: SignalLike) -> Instances:
    """The subscriber and publisher of `plan`, wired through FIFOs; `ports`: `loopback_ports`."""
    clk, rst = ports["clk"], ports["rst"]
    sub = port_signals(ports_of(plan, Side.SUBSCRIBER))
    pub = port_signals(ports_of(plan, Side.PUBLISHER))
    for port in ports_of(plan, Side.PUBLISHER):
        if port.group == ROOT and port.role in DATA_ROLES:
            pub[port.name] = sub[port.name]
    pub["msg_valid"] = sub["msg_valid"]
    sub["msg_ready"] = pub["msg_ready"]
    for name in ("s_axis_tdata", "s_axis_tkeep", "s_axis_tvalid", "s_axis_tready", "s_axis_tlast"):
        sub[name] = ports[name]
    for name in ("m_axis_tdata", "m_axis_tkeep", "m_axis_tvalid", "m_axis_tready", "m_axis_tlast"):
        pub[name] = ports[name]
    sub["error_count"] = ports["error_count"]
    sub["error_reason"] = Signal(intbv(0)[REASON_BITS:])  # the loopback reports the count only
    pub["frame_length"] = ports["frame_length"]
    if plan.store_and_forward:
        pub["error_count"] = Signal(intbv(0)[COUNTER_BITS:])  # overflows: none, by sizing
    blocks = [follow(sub["msg_valid"], ports["fields_valid"])]
    blocks.append(stream_buffers(plan, clk, rst, sub, pub))
    blocks.append(rfc_subscriber(plan, clk=clk, rst=rst, **sub))
    blocks.append(rfc_publisher(plan, clk=clk, rst=rst, **pub))
    return blocks
