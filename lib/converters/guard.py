"""Store and forward in front of a subscriber whose messages carry strings or sequences.

Such a subscriber hands its strings and sequences on as sub-streams while the frame arrives, so
a frame found malformed at its end would already have reached the consumer in part. The guard
holds the whole frame in block RAM while a second instance of the same subscriber (the
*checker*, every output taken at once) parses it; only when the checker finds it well formed
does the guard send the frame on to the real subscriber, else it drops it and counts it by
reason (`rfc.lib.converters.malformed.Reason`). One frame at a time: the cost is one frame's
transfer of latency and a buffer of the largest frame the maxima allow. A frame longer than the
buffer cannot be well formed; it is dropped as ``maximum`` unless the checker names a reason.
"""

from __future__ import annotations

from enum import IntEnum
from typing import Any

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.axi_stream import STREAM, AxiStream
from rfc.lib.converters.checker import checker_ports, checker_signals, without_fields
from rfc.lib.converters.malformed import DROP_REASONS, Reason, counter_name, reason_counter
from rfc.lib.converters.ports import COUNTER_BITS, REASON_BITS, Direction, Port, PortRole
from rfc.lib.converters.ram import ram
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.subscriber import rfc_subscriber
from rfc.lib.passthrough import take_all
from rfc.lib.slice import SliceSide, parts_slice
from rfc.lib.types import Instances, SignalLike


class _State(IntEnum):
    STORE = 0  # taking the frame into the buffer and the checker
    VERDICT = 1  # the frame is in; waiting for the checker's record
    SEND = 2  # sending the buffered frame to the subscriber


def guard_ports(width: int) -> list[Port]:
    """The guard's ports for a bus of `width` bytes, in declaration order."""
    ports = [Port("clk", 1, Direction.IN, PortRole.CLOCK), Port("rst", 1, Direction.IN,
             PortRole.RESET)]  # fmt: skip
    for bus, out, into in (
        ("s_axis", Direction.IN, Direction.OUT),
        ("m_axis", Direction.OUT, Direction.IN),
    ):
        ports += [
            Port(f"{bus}_tdata", 8 * width, out, PortRole.TDATA, bus),
            Port(f"{bus}_tkeep", width, out, PortRole.TKEEP, bus),
            Port(f"{bus}_tvalid", 1, out, PortRole.TVALID, bus),
            Port(f"{bus}_tready", 1, into, PortRole.TREADY, bus),
            Port(f"{bus}_tlast", 1, out, PortRole.TLAST, bus),
        ]
    ports += [
        Port(counter_name(r), COUNTER_BITS, Direction.OUT, PortRole.ERROR_COUNT)
        for r in DROP_REASONS
    ]
    return ports


@block
def frame_guard(plan: Plan, depth: int, **ports: Any) -> Any:
    """Check each frame of `plan` whole before it reaches the subscriber; `ports`: `guard_ports`.

    Args:
        plan: The subscriber's plan (the checker is built from it).
        depth: Beats the buffer holds: the largest well-formed frame.
        ports: One signal per name of `guard_ports`.
    """
    clk, rst = ports["clk"], ports["rst"]
    s_tdata, s_tkeep, s_tvalid, s_tready, s_tlast = AxiStream.named(ports, "s_axis").signals()
    inner, outer = guard_stream(ports), AxiStream.named(ports, "m_axis")
    m_tdata, m_tkeep, m_tvalid, m_tready, m_tlast = inner.signals()
    full_keep = (1 << plan.width) - 1
    state = Signal(intbv(0, min=0, max=len(_State)))
    written = Signal(intbv(0, min=0, max=depth + 1))
    read = Signal(intbv(0, min=0, max=depth + 1))
    overflow = Signal(bool(0))
    last_keep = Signal(intbv(0)[plan.width :])
    out_valid, out_last = Signal(bool(0)), Signal(bool(0))
    w_enable, r_enable = Signal(bool(0)), Signal(bool(0))
    address = Signal(intbv(0, min=0, max=max(2, depth)))
    r_address = Signal(intbv(0, min=0, max=max(2, depth)))
    r_data = Signal(intbv(0)[8 * plan.width :])
    c_valid, c_ready = Signal(bool(0)), Signal(bool(0))
    drop, reason = Signal(bool(0)), Signal(intbv(0)[REASON_BITS:])

    checking = without_fields(plan)
    checker, readies = checker_signals(checking)
    verdict, failed = checker["msg_valid"], checker["msg_error"]
    cause = Signal(intbv(0)[REASON_BITS:])
    inputs = (s_tdata, s_tkeep, c_valid, c_ready, s_tlast)
    parser = rfc_subscriber(checking, **checker_ports(clk, rst, inputs, cause, checker))
    storing, waiting, sending = int(_State.STORE), int(_State.VERDICT), int(_State.SEND)
    maximum = int(Reason.MAXIMUM)

    @always_comb
    def take() -> None:
        s_tready.next = state == storing and c_ready
        c_valid.next = state == storing and s_tvalid
        w_enable.next = state == storing and s_tvalid and c_ready and written < depth
        r_enable.next = state == sending and read < written and (not out_valid or m_tready)
        drop.next = state == waiting and verdict and (failed or overflow)
        reason.next = maximum
        if failed:
            reason.next = cause

    addresses = buffer_addresses(written, read, depth, address, r_address)

    # Drives the output from this guard's registers, as the slice and the mux do from theirs.
    @always_comb
    def give() -> None:
        m_tdata.next = r_data
        m_tvalid.next = out_valid
        m_tlast.next = out_last
        m_tkeep.next = full_keep
        if out_last:
            m_tkeep.next = last_keep

    @always_seq(clk.posedge, reset=rst)
    def control() -> None:
        if state == storing:
            if s_tvalid and c_ready:
                if written < depth:
                    written.next = written + 1
                else:
                    overflow.next = True
                if s_tlast:
                    last_keep.next = s_tkeep
                    state.next = waiting
        elif state == waiting:
            if verdict:
                if failed or overflow:
                    state.next = storing
                    written.next = 0
                    overflow.next = False
                else:
                    state.next = sending
                    read.next = 0
        else:
            if r_enable:
                read.next = read + 1
                out_valid.next = True
                out_last.next = read + 1 == written
            elif m_tready:
                out_valid.next = False
            if out_valid and m_tready and out_last:
                out_valid.next = False
                out_last.next = False
                state.next = storing
                written.next = 0
                read.next = 0

    memory = ram(clk, w_enable, address, s_tdata, r_enable, r_address, r_data, depth)
    counters = [
        reason_counter(clk, rst, drop, drop, reason, ports[counter_name(r)], int(r))
        for r in DROP_REASONS
    ]
    held = [take_all(clk, rst, ready) for ready in readies]  # the checker takes everything
    out = registered_output(clk, rst, inner, outer)
    return parser, take, addresses, give, control, memory, counters, held, out


# A small block's shape (as publisher.draining_ready's); its logic, a clamp, is the guards' own.
@block
def buffer_addresses(
    written: SignalLike, read: SignalLike, depth: int, address: SignalLike, r_address: SignalLike
) -> Instances:
    """A guard's RAM addresses: beats `written` and `read` so far, 0 once they reach `depth`."""

    @always_comb
    def clamp() -> None:
        address.next = 0
        if written < depth:
            address.next = written
        r_address.next = 0
        if read < depth:
            r_address.next = read

    return clamp


def guard_stream(ports: dict[str, SignalLike]) -> AxiStream:
    """Signals like the guard's ``m_axis`` ports."""
    return AxiStream(*(
        Signal(intbv(0)[len(ports[f"m_axis_{n}"]) :]) if n in ("tdata", "tkeep")
        else Signal(bool(0))
        for n in STREAM
    ))  # fmt: skip


@block
def registered_output(
    clk: SignalLike, rst: SignalLike, inner: AxiStream, outer: AxiStream
) -> Instances:
    """Hand the stream a guard drives (`inner`) on to its ports (`outer`) through a slice.

    Everything the guard hands its subscriber then comes from a flip-flop: no path runs from
    the guard's logic into the subscriber's. The slice adds a cycle of latency, not of
    throughput.
    """
    data, keep, valid, ready, last = inner.signals()
    m_data, m_keep, m_valid, m_ready, m_last = outer.signals()
    source = SliceSide([data, keep, last], valid, ready)
    return parts_slice(clk, rst, source, SliceSide([m_data, m_keep, m_last], m_valid, m_ready))
