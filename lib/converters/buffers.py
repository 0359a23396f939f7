"""Buffers in front of a publisher: one message's strings, sequences and elements.

A publisher takes a message's record first — it needs every length to compute the frame length
before the first payload beat — and its strings, sequences and sequence elements after. A
producer that hands those over before its record (a subscriber does, while it parses; so does
an accelerator that passes them through) would stall against it. `stream_buffers` puts a FIFO
on each sub-stream and element channel, sized from the plan's maxima to hold one message;
`buffered_publisher` is a publisher with those FIFOs inside, with the publisher's own ports.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.buffer_sizes import DATA_ROLES, Buffer, buffers_of, element_ports
from rfc.lib.converters.fifo import fifo
from rfc.lib.converters.ports import Port, Side, dma_ports, ports_of
from rfc.lib.converters.publisher import rfc_publisher
from rfc.lib.converters.steps import Payload, Plan
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.slice import part_of
from rfc.lib.types import Instances, SignalLike

# the sizes are reexported: the system's lowering takes both from here
__all__ = [
    "DATA_ROLES",
    "Buffer",
    "buffered_ports",
    "buffered_publisher",
    "buffers_of",
    "stream_buffers",
]


@block
def stream_buffers(
    plan: Plan,
    clk: SignalLike,
    rst: SignalLike,
    producer: dict[str, SignalLike],
    publisher: dict[str, SignalLike],
) -> Instances:
    """FIFOs from `producer`'s sub-streams and element channels to `publisher`'s.

    Both map the publisher's accelerator-side port names to signals.
    """
    ports = ports_of(plan, Side.PUBLISHER)
    blocks = []
    for buffer in buffers_of(plan):
        name = buffer.channel
        if f"{name}_tdata" in publisher:
            blocks.append(
                fifo(clk, rst, producer[f"{name}_tdata"], producer[f"{name}_tvalid"],
                     producer[f"{name}_tready"], publisher[f"{name}_tdata"],
                     publisher[f"{name}_tvalid"], publisher[f"{name}_tready"], buffer.words)
            )  # fmt: skip
            continue
        data = [p.name for p in element_ports(ports, name)]
        # One word per element (a lone bool padded: ConcatSignal needs two parts).
        parts = [producer[p] for p in reversed(data)] or [intbv(0)[1:]]
        word_in = ConcatSignal(intbv(0)[1:], *parts) if len(parts) == 1 else ConcatSignal(*parts)
        word_out = Signal(intbv(0)[len(word_in) :])
        blocks.append(
            fifo(clk, rst, word_in, producer[f"{name}_valid"], producer[f"{name}_ready"],
                 word_out, publisher[f"{name}_valid"], publisher[f"{name}_ready"], buffer.words)
        )  # fmt: skip
        low = 0
        for port in data:
            target = publisher[port]
            blocks.append(part_of(word_out, low, len(target), isinstance(target.val, bool), target))
            low += len(target)
    return blocks


def buffered_ports(plan: Plan) -> tuple[Port, ...]:
    """The buffered publisher's ports: the publisher's own, DMA side first."""
    return (*dma_ports(plan, Side.PUBLISHER), *ports_of(plan, Side.PUBLISHER))


@block
def occupancy(
    clk: SignalLike,
    rst: SignalLike,
    pushed: SignalLike,
    in_ready: SignalLike,
    popped: SignalLike,
    out_ready: SignalLike,
    empty: SignalLike,
    depth: int,
) -> Instances:
    """`empty` while a FIFO of `depth` words holds nothing, counted from both handshakes.

    Exact on the cycle after a push, when the FIFO's own output shows nothing yet.
    """
    count = Signal(intbv(0, min=0, max=depth + 4))

    @always_comb
    def status() -> None:
        empty.next = count == 0

    @always_seq(clk.posedge, reset=rst)
    def track() -> None:
        arriving = pushed and in_ready
        leaving = popped and out_ready
        if arriving and not leaving:
            count.next = count + 1
        elif leaving and not arriving:
            count.next = count - 1

    return status, track


@block
def buffered_publisher(plan: Plan, **ports: SignalLike) -> Instances:
    """The publisher of `plan` behind `stream_buffers`; `ports`: `buffered_ports`.

    Behind a record-first producer it also tells the publisher which of the message's own
    strings' FIFOs are empty, so that a string shorter than its length cannot stall it.
    """
    clk, rst = ports["clk"], ports["rst"]
    buffers = buffers_of(plan)
    buffered = {b.channel for b in buffers}
    inner = dict(ports)
    inner.update(port_signals([p for p in ports_of(plan, Side.PUBLISHER) if p.group in buffered]))
    blocks = [stream_buffers(plan, clk, rst, ports, inner)]
    held = {}
    if plan.streamed_last is not None:
        top = {s.stream for s in plan.steps if isinstance(s, Payload) and s.channel == 0}
        for buffer in buffers:
            name = buffer.channel
            if name in top:
                held[name] = Signal(bool(1))
                blocks.append(
                    occupancy(clk, rst, ports[f"{name}_tvalid"], ports[f"{name}_tready"],
                              inner[f"{name}_tvalid"], inner[f"{name}_tready"], held[name],
                              buffer.words)
                )  # fmt: skip
    blocks.append(rfc_publisher(plan, held=held, **inner))
    return blocks
