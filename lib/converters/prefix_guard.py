"""A frame guard that holds only the frame's prefix, for messages that end in one big sequence.

The whole-frame guard (`rfc.lib.converters.guard`) needs a buffer of the largest frame: about
1,500 block RAMs of 36 Kb for a full-HD sensor_msgs/Image, ten times an xc7z020. When the
message's last field is a primitive sequence (``uint8[] data``) and no sequence of messages or
strings comes before it, every length of the frame is known once the sequence starts. This
guard then holds only the bytes up to there: a checker (a second subscriber that parses every
field, all its outputs taken at once) reads them while they are stored, and when it starts the
sequence the guard compares the message's size (the frame-length circuit of its lengths) with
the frame's size its chunk header declared (`rfc.lib.converters.chunk_length.dma_tap`):

- the checker already found the frame malformed (a string over its maximum or without its
  NUL, a sequence over its maximum, a wrong CDR encapsulation): dropped, its reason counted;
- the declared size is shorter than the message (``truncated``) or longer than the message
  and ROS 2's padding to 4 (``trailing``): dropped;
- else the stored prefix goes to the subscriber and the rest of the frame follows it straight
  from the bus, a beat per cycle.

A frame that ends before its last sequence starts is checked whole, as the whole-frame guard
does. What the check cannot see is a DMA that ends the chunk before (or after) the length its
header declares: the subscriber still finds that frame truncated (or trailing) at its end and
raises ``msg_error``, but part of the sequence has reached the consumer by then.
"""

from __future__ import annotations

from enum import IntEnum
from typing import Any

from myhdl import ResetSignal, Signal, always, always_comb, always_seq, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.checker import checker_ports, checker_signals, without_fields
from rfc.lib.converters.chunk_length import LENGTH_BITS
from rfc.lib.converters.frame_length import frame_length_circuit, length_formula
from rfc.lib.converters.guard import (
    buffer_addresses,
    guard_ports,
    guard_stream,
    registered_output,
)
from rfc.lib.converters.malformed import DROP_REASONS, Reason, counter_name, reason_counter
from rfc.lib.converters.ports import REASON_BITS, Direction, Port, PortRole
from rfc.lib.converters.ram import ram
from rfc.lib.converters.steps import Payload, Plan
from rfc.lib.converters.subscriber import rfc_subscriber
from rfc.lib.passthrough import take_all

#: The port giving the frame's size as the chunk header declared it.
DECLARED = "frame_length"


class _State(IntEnum):
    STORE = 0  # taking the prefix into the buffer and the checker
    REPLAY = 1  # sending the stored beats to the subscriber
    PASS = 2  # the rest of the frame, straight from the bus
    DROP = 3  # consuming the rest of a rejected frame


def prefix_guard_ports(width: int) -> list[Port]:
    """The guard's ports for a bus of `width` bytes: the frame guard's, and the declared size."""
    ports = guard_ports(width)
    counters = len(ports) - len(DROP_REASONS)  # the streams, then the counters
    declared = Port(DECLARED, LENGTH_BITS, Direction.IN, PortRole.FIELD)
    return [*ports[:counters], declared, *ports[counters:]]


@block
def prefix_guard(checking: Plan, depth: int, **ports: Any) -> Any:
    """Check each frame's prefix before it reaches the subscriber; `ports`: `prefix_guard_ports`.

    Args:
        checking: The checker's plan (`checking_plan`).
        depth: Beats the buffer holds: the longest frame whose last sequence is empty, and
            `SLACK_BEATS`.
        ports: One signal per name of `prefix_guard_ports`.
    """
    checking = without_fields(checking)
    clk, rst = ports["clk"], ports["rst"]
    s_tdata, s_tkeep, s_tvalid, s_tready, s_tlast = AxiStream.named(ports, "s_axis").signals()
    inner, outer = guard_stream(ports), AxiStream.named(ports, "m_axis")
    m_tdata, m_tkeep, m_tvalid, m_tready, m_tlast = inner.signals()
    header = ports[DECLARED]
    declared = Signal(intbv(0)[LENGTH_BITS:])  # taken with the frame's first beat
    last = checking.steps[-2]
    assert isinstance(last, Payload)
    width = checking.width
    full_keep = (1 << width) - 1
    state = Signal(intbv(0, min=0, max=len(_State)))
    written = Signal(intbv(0, min=0, max=depth + 1))
    read = Signal(intbv(0, min=0, max=depth + 1))
    ended, overflow = Signal(bool(0)), Signal(bool(0))
    last_keep = Signal(intbv(0)[width:])
    out_valid, out_last = Signal(bool(0)), Signal(bool(0))
    w_enable, r_enable, taken = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    address = Signal(intbv(0, min=0, max=max(2, depth)))
    r_address = Signal(intbv(0, min=0, max=max(2, depth)))
    r_data = Signal(intbv(0)[8 * width :])
    c_valid, c_ready = Signal(bool(0)), Signal(bool(0))
    drop, reason = Signal(bool(0)), Signal(intbv(0)[REASON_BITS:])
    decided = Signal(bool(0))
    c_rst = ResetSignal(rst.active, active=rst.active, isasync=rst.isasync)
    allowed = Signal(intbv(0)[LENGTH_BITS + 2 :])

    checker, readies = checker_signals(checking)
    verdict, failed = checker["msg_valid"], checker["msg_error"]
    started = checker[f"{last.stream}_tvalid"]
    cause = Signal(intbv(0)[REASON_BITS:])
    inputs = (s_tdata, s_tkeep, c_valid, c_ready, s_tlast)
    parser = rfc_subscriber(checking, **checker_ports(clk, c_rst, inputs, cause, checker))
    counts = {s.port: checker[s.port] for s in length_formula(checking).stages if s.port}
    size = Signal(intbv(0)[LENGTH_BITS + 2 :])
    sizing = frame_length_circuit(checking, counts, size)
    # the size and its padded bound are judged a cycle after the last sequence starts, from
    # registers: the frame-length circuit and the comparisons are then two paths, not one
    size_held, allowed_held = (
        Signal(intbv(0)[LENGTH_BITS + 2 :]),
        Signal(intbv(0)[LENGTH_BITS + 2 :]),
    )
    was_started = Signal(bool(0))
    storing, replaying, passing, dropping = (int(s) for s in _State)
    maximum, truncated, trailing = int(Reason.MAXIMUM), int(Reason.TRUNCATED), int(Reason.TRAILING)

    @always_comb
    def take() -> None:
        taking = state == storing and c_rst != c_rst.active and not ended
        c_valid.next = taking and s_tvalid
        taken.next = taking and s_tvalid and c_ready
        w_enable.next = taking and s_tvalid and c_ready and written < depth
        if state == passing:
            s_tready.next = m_tready
        elif state == dropping:
            s_tready.next = 1
        else:
            s_tready.next = taking and c_ready
        r_enable.next = state == replaying and read < written and (not out_valid or m_tready)

    @always_comb
    def cdr_pad() -> None:  # ROS 2 may pad the frame to a multiple of 4
        allowed.next = size
        if size[2:0] != 0:
            allowed.next = size + 4 - size[2:0]

    @always_comb
    def no_pad() -> None:
        allowed.next = size

    pad = cdr_pad if checking.is_cdr else no_pad

    @always(clk.posedge)
    def hold_size() -> None:
        size_held.next = size
        allowed_held.next = allowed
        was_started.next = state == storing and c_rst != c_rst.active and started

    @always_comb
    def judge() -> None:
        # Once the checker has started the last sequence every length is known; a frame that
        # ends before is judged by the checker alone, as a whole.
        judging = state == storing and c_rst != c_rst.active
        decided.next = judging and (verdict or was_started)
        ok = False
        reason.next = maximum
        if failed:
            reason.next = cause
        elif overflow:
            reason.next = maximum
        elif was_started and declared < size_held:
            reason.next = truncated
        elif was_started and declared > allowed_held:
            reason.next = trailing
        else:
            ok = True  # the checker's verdict, or a started frame of the declared size
        drop.next = judging and (verdict or was_started) and not ok

    addresses = buffer_addresses(written, read, depth, address, r_address)

    # The frame guard's `give` (which has no PASS to select), and the bus straight through in PASS.
    @always_comb
    def give() -> None:
        if state == passing:
            m_tdata.next = s_tdata
            m_tkeep.next = s_tkeep
            m_tvalid.next = s_tvalid
            m_tlast.next = s_tlast
        else:
            m_tdata.next = r_data
            m_tvalid.next = out_valid
            m_tlast.next = out_last
            m_tkeep.next = full_keep
            if out_last:
                m_tkeep.next = last_keep

    @always(clk.posedge)
    def clear_checker() -> None:
        # the checker starts afresh for every frame (a register: no glitch reaches its reset)
        c_rst.next = rst == rst.active or state != storing or decided

    # Stores a beat as `frame_guard`'s control does: a step of each guard's own state machine,
    # whose other states clear what it stores. Shared, it would change both guards' VHDL,
    # which the equivalence checker cannot prove (a guard holds a subscriber).
    @always_seq(clk.posedge, reset=rst)
    def control() -> None:
        done = False  # the frame is over: back to STORE, the buffer empty
        if state == storing:
            if taken:
                if written == 0 and not overflow:
                    declared.next = header
                if written < depth:
                    written.next = written + 1
                else:
                    overflow.next = True
                if s_tlast:
                    last_keep.next = s_tkeep
                    ended.next = True
            if decided:
                if drop:
                    if ended or verdict or (taken and s_tlast):
                        done = True
                    else:
                        state.next = dropping
                else:
                    state.next = replaying
                    read.next = 0
        elif state == replaying:
            if r_enable:
                read.next = read + 1
                out_valid.next = True
                out_last.next = ended and read + 1 == written
            elif m_tready:
                out_valid.next = False
            if out_valid and m_tready and read == written:
                out_valid.next = False
                out_last.next = False
                if ended:
                    done = True
                else:
                    state.next = passing
        elif s_tvalid and s_tready and s_tlast:  # passing or dropping: the frame's end
            done = True
        if done:
            state.next = storing
            written.next = 0
            read.next = 0
            ended.next = False
            overflow.next = False

    memory = ram(clk, w_enable, address, s_tdata, r_enable, r_address, r_data, depth)
    out = registered_output(clk, rst, inner, outer)
    counters = [
        reason_counter(clk, rst, drop, drop, reason, ports[counter_name(r)], int(r))
        for r in DROP_REASONS
    ]
    held = [take_all(clk, rst, ready) for ready in readies]  # the checker takes everything
    return (
        parser, sizing, take, addresses, pad, hold_size, judge, give, clear_checker, control,
        memory, counters, held, out,
    )  # fmt: skip
