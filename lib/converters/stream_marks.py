"""``tkeep`` and ``tlast`` for a sub-stream that has only its length: accelerator to accelerator.

An accelerator's output sub-stream has ``tdata``, ``tvalid``, ``tready`` and its length, as a
publisher takes it (docs/converters.md); the next accelerator's input has ``tkeep`` and
``tlast`` too, as a subscriber gives them. `stream_marks` watches the beats of each message
and derives both from the length: every beat full but the last.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.ports import Direction, Port, PortRole
from rfc.lib.types import Instances, SignalLike


def marks_ports(length_bits: int, beat: int) -> list[Port]:
    """The ports of `stream_marks` for a length of `length_bits` and beats of `beat` bytes."""
    into, out = Direction.IN, Direction.OUT
    return [
        Port("clk", 1, into, PortRole.CLOCK),
        Port("rst", 1, into, PortRole.RESET),
        Port("length", length_bits, into, PortRole.LENGTH),
        Port("tvalid", 1, into, PortRole.TVALID),
        Port("tready", 1, into, PortRole.TREADY),
        Port("tkeep", beat, out, PortRole.TKEEP),
        Port("tlast", 1, out, PortRole.TLAST),
    ]


@block
def stream_marks(element_size: int, **ports: SignalLike) -> Instances:
    """Keep and last of each beat; a beat taken with none of the message left starts one."""
    clk, rst, length = ports["clk"], ports["rst"], ports["length"]
    tvalid, tready, tkeep, tlast = ports["tvalid"], ports["tready"], ports["tkeep"], ports["tlast"]
    beat = len(tkeep)
    per_beat = beat // element_size
    remaining = Signal(intbv(0)[len(length) :])
    due = Signal(intbv(0)[len(length) :])

    @always_comb
    def count() -> None:
        if remaining == 0:
            due.next = length
        else:
            due.next = remaining

    @always_comb
    def marks() -> None:
        tlast.next = due <= per_beat
        keep = intbv(0)[beat:]
        for lane in range(beat):
            keep[lane] = due > lane // element_size
        tkeep.next = keep

    @always_seq(clk.posedge, reset=rst)
    def track() -> None:
        if tvalid and tready:
            if due > per_beat:
                remaining.next = due - per_beat
            else:
                remaining.next = 0

    return count, marks, track
