"""Why a subscriber rejected a frame, and the gate that keeps rejected frames from the logic.

The subscriber presents every frame's record, a malformed one with ``msg_error`` set and its
reason on ``error_reason`` (`Reason`). Behind a subscriber of fixed-size fields the top level
puts a `drop_gate`: a rejected record is taken by the gate itself — its consumer never sees
``valid`` for it — and counted per reason, so the processor can read how many frames each
subscriber dropped and why (docs/protocol.md, status registers). A subscriber that streams
strings or sequences gets a frame guard in front instead (`rfc.lib.converters.guard`).
"""

from __future__ import annotations

from enum import IntEnum

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.ports import COUNTER_BITS, REASON_BITS, Direction, Port, PortRole
from rfc.lib.types import Instances, SignalLike


class Reason(IntEnum):
    """Why a frame was rejected, as the subscriber's ``error_reason`` carries it."""

    NONE = 0
    #: The frame ended (``tlast``) before the message did.
    TRUNCATED = 1
    #: A string or sequence longer than the maximum the converter was built for.
    MAXIMUM = 2
    #: Bytes after the message beyond ROS 2's padding to 4.
    TRAILING = 3
    #: Not the encoding of the type: a wrong CDR encapsulation, a CDR string without its NUL.
    ENCODING = 4

    @property
    def label(self) -> str:
        """Its name in counters, ports and reports (``truncated``)."""
        return self.name.lower()


#: The reasons a frame can be dropped for, in the order of the status registers.
DROP_REASONS = tuple(r for r in Reason if r is not Reason.NONE)


def counter_name(reason: Reason) -> str:
    """The gate's port counting frames dropped for `reason` (``dropped_truncated``)."""
    return f"dropped_{reason.label}"


def status_port(subscriber: int, reason: Reason) -> str:
    """The system top level's count of frames subscriber `subscriber` dropped for `reason`."""
    return f"status_sub{subscriber}_{reason.label}"


def gate_ports() -> list[Port]:
    """The ports of `drop_gate`, in declaration order."""
    into, out = Direction.IN, Direction.OUT
    return [
        Port("clk", 1, into, PortRole.CLOCK),
        Port("rst", 1, into, PortRole.RESET),
        Port("s_valid", 1, into, PortRole.VALID),
        Port("s_ready", 1, out, PortRole.READY),
        Port("s_error", 1, into, PortRole.ERROR),
        Port("s_reason", REASON_BITS, into, PortRole.ERROR_REASON),
        Port("m_valid", 1, out, PortRole.VALID),
        Port("m_ready", 1, into, PortRole.READY),
        *(Port(counter_name(r), COUNTER_BITS, out, PortRole.ERROR_COUNT) for r in DROP_REASONS),
    ]


@block
def reason_counter(
    clk: SignalLike,
    rst: SignalLike,
    s_valid: SignalLike,
    s_error: SignalLike,
    s_reason: SignalLike,
    count: SignalLike,
    code: int,
) -> Instances:
    """Count the rejected records whose reason is `code` into `count`."""
    tally = Signal(intbv(0)[len(count) :])

    @always_seq(clk.posedge, reset=rst)
    def step() -> None:
        if s_valid and s_error and s_reason == code:
            tally.next = tally + 1  # as the subscriber's error_count: 2**32 frames are out of reach

    @always_comb
    def show() -> None:
        count.next = tally

    return step, show


@block
def drop_gate(**ports: SignalLike) -> Instances:
    """Pass valid records on; take rejected ones here and count them by reason.

    `ports` holds one signal per name of `gate_ports`. A valid record's handshake goes straight
    through (the gate adds no cycle). A rejected one is taken on the first cycle its consumer's
    `m_ready` is high, or else on the next cycle, from a flip-flop of the gate's own: `s_ready`
    is the consumer's ready (a register slice's flip-flop in a generated system) or that one,
    never the subscriber's verdict, so no path runs from the subscriber through the gate back
    into it. A consumer that waits for `m_valid` before its ready still lets rejected records go.
    """
    clk, rst = ports["clk"], ports["rst"]
    s_valid, s_ready, s_error = ports["s_valid"], ports["s_ready"], ports["s_error"]
    m_valid, m_ready = ports["m_valid"], ports["m_ready"]
    dropping = Signal(bool(0))  # a rejected record waits for its acknowledgement
    dropped = Signal(bool(0))  # a rejected record is taken on this cycle

    @always_seq(clk.posedge, reset=rst)
    def wait_to_drop() -> None:
        dropping.next = s_valid and s_error and not m_ready and not dropping

    @always_comb
    def handshake() -> None:
        m_valid.next = s_valid and not s_error
        s_ready.next = m_ready or dropping
        dropped.next = s_valid and s_error and (m_ready or dropping)

    counters = [
        reason_counter(
            clk, rst, dropped, dropped, ports["s_reason"], ports[counter_name(r)], int(r)
        )
        for r in DROP_REASONS
    ]
    return wait_to_drop, handshake, counters
