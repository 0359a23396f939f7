"""The subscriber's outputs besides field registers: lengths, element handshakes, sub-streams.

Lengths and counts are registers written when their step begins. Element channels signal
``valid`` while the parser waits at the element's Next step, once every sub-stream beat before
it has been taken, with ``last`` on the final element.
All sub-streams share one output register; each stream's ports see it, and its ``tvalid``
only while the register holds one of its beats.
"""

from __future__ import annotations

from myhdl import always_comb, always_seq, block

from rfc.lib.converters.steps import Loop, Plan
from rfc.lib.converters.tables import tables
from rfc.lib.converters.wiring import bits_of, follow, index_bit
from rfc.lib.types import Instances, SignalLike


# One clocked process, the shape of many small blocks: here a register loaded at one step.
@block
def length_register(
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    pc: SignalLike,
    at: int,
    value: SignalLike,
    port: SignalLike,
) -> Instances:
    """Write `value` to `port` when step `at` begins (`fire`)."""

    @always_seq(clk.posedge, reset=rst)
    def write() -> None:
        if fire and pc == at:
            port.next = value[len(port) :]

    return write


# A plan, its ports and the control's signals, as every part of a converter takes them.
@block
def length_registers(
    plan: Plan,
    ports: dict[str, SignalLike],
    clk: SignalLike,
    rst: SignalLike,
    fire: SignalLike,
    pc: SignalLike,
    value: SignalLike,
) -> Instances:
    """One `length_register` per selected string or sequence."""
    return [
        length_register(clk, rst, fire, pc, at, value, ports[name])
        for at, name in plan.length_ports()
    ]


@block
def element_handshake(
    pc: SignalLike,
    at: int,
    busy: SignalLike,
    counter: SignalLike,
    valid: SignalLike,
    last: SignalLike,
) -> Instances:
    """An element is valid while the parser waits at its Next step (`at`), streams sent."""

    @always_comb
    def status() -> None:
        valid.next = pc == at and not busy
        last.next = counter == 1

    return status


# A plan, its ports and the control's signals, as every part of a converter takes them.
@block
def element_handshakes(
    plan: Plan,
    ports: dict[str, SignalLike],
    pc: SignalLike,
    busy: SignalLike,
    counters: list[SignalLike],
) -> Instances:
    """One `element_handshake` per selected element channel."""
    loops = [step for step in plan.steps if isinstance(step, Loop)]
    blocks = []
    for loop, counter in zip(loops, counters, strict=True):
        channel = plan.channels[loop.element_channel]
        if channel.selected:
            valid, last = ports[f"{channel.name}_valid"], ports[f"{channel.name}_last"]
            blocks.append(element_handshake(pc, loop.next, busy, counter, valid, last))
    return blocks


@block
def stream_port(
    o_data: SignalLike,
    o_keep: SignalLike,
    o_last: SignalLike,
    o_valid: SignalLike,
    o_stream: SignalLike,
    index: int,
    tdata: SignalLike,
    tkeep: SignalLike,
    tvalid: SignalLike,
    tlast: SignalLike,
) -> Instances:
    """The ports of sub-stream `index`, driven from the shared output register."""

    @always_comb
    def drive() -> None:
        tdata.next = o_data[len(tdata) :]
        tkeep.next = o_keep[len(tkeep) :]
        tvalid.next = o_valid and o_stream == index
        tlast.next = o_last

    return drive


@block
def stream_outputs(
    plan: Plan,
    ports: dict[str, SignalLike],
    o_data: SignalLike,
    o_keep: SignalLike,
    o_last: SignalLike,
    o_valid: SignalLike,
    o_stream: SignalLike,
    o_ready: SignalLike,
) -> Instances:
    """Every sub-stream's ports; `o_ready` is the ready of the stream the register serves."""
    blocks = []
    readies = []
    for index, at in enumerate(tables(plan).streams):
        name = plan.payload(at).stream
        blocks.append(
            stream_port(
                o_data,
                o_keep,
                o_last,
                o_valid,
                o_stream,
                index,
                ports[f"{name}_tdata"],
                ports[f"{name}_tkeep"],
                ports[f"{name}_tvalid"],
                ports[f"{name}_tlast"],
            )
        )
        readies.append(ports[f"{name}_tready"])
    if len(readies) > 1:
        blocks.append(index_bit(bits_of(readies), o_stream, o_ready))
    elif readies:
        blocks.append(follow(readies[0], o_ready))
    return blocks
