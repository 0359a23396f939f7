"""Where each byte a publisher sends comes from: per-lane multiplexers over fixed sources.

Record chunk ``rc`` puts, on bus lane ``j``, one byte known at compile time: a byte of a field
input, of a length prefix, of the CDR header, or a zero (padding, excluded fields). So each
lane gets a bus of just the bytes it ever carries and a table from ``rc`` to a position in it:
a multiplexer as wide as the number of chunks, not as the message. Payload bytes work the same
way with the sub-streams' data inputs, indexed by stream and piece.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Constant, Signal, always_comb, block, intbv

from rfc.lib.converters.frame_length import accumulate
from rfc.lib.converters.steps import Loop, Payload, Plan, SlotRole, Step
from rfc.lib.converters.tables import pieces, tables
from rfc.lib.types import Instances, SignalLike

#: The four bytes of a little-endian plain-CDR encapsulation header.
CDR_HEADER = (0x00, 0x01, 0x00, 0x00)


# Selects a byte by a table where `wiring.select_bit` selects a bit: another VHDL process.
@block
def lane_select(
    bus: SignalLike, table: tuple[int, ...], index: SignalLike, out: SignalLike
) -> Instances:
    """Drive `out` with byte ``table[index]`` of `bus`."""

    @always_comb
    def select() -> None:
        at = table[index]
        for bit in range(8):
            out.next[bit] = bus[8 * at + bit]

    return select


def _byte(source: SignalLike, index: int) -> list[SignalLike]:
    """Byte `index` of a signal as parts of a `ConcatSignal`, high first (a bool: 0 or 1).

    Parts are signals, slices and constants only: MyHDL converts a `ConcatSignal` nested in
    another as its initial value, so every bus is built flat from such parts.
    """
    if len(source) == 1:
        return [intbv(0)[7:], source]
    return [source(8 * index + 8, 8 * index)]


@block
def record_sources(
    plan: Plan, ports: dict[str, SignalLike], rc: SignalLike, lanes: list[SignalLike]
) -> Instances:
    """Drive ``lanes[j]`` with the byte record chunk `rc` sends on lane j."""
    t = tables(plan)
    width = plan.width
    entries: list[list[SignalLike]] = [[] for _ in range(width)]
    table = [[0] * t.record_chunks for _ in range(width)]
    zero = [intbv(0)[8:]]
    header = [[intbv(value)[8:]] for value in CDR_HEADER]
    blocks = []
    for pc, step in plan.records():
        for slot in step.slots:
            if slot.role is SlotRole.ENCAPSULATION:
                value = None
            elif slot.role is SlotRole.LENGTH:
                port, terminator = _prefixed(plan.steps[pc + 1])
                if port:
                    value = Signal(intbv(0)[32:])
                    # the uint32 a prefix carries: the count, plus the NUL of a CDR string
                    blocks.append(accumulate(ports[port], terminator, value))
                elif terminator:
                    value = Constant(intbv(terminator)[32:])  # an empty CDR string: its NUL
                else:
                    continue
            elif slot.port:
                value = ports[slot.port]
            else:
                continue
            for run in pieces(slot, t.base[pc], width):
                for i in range(run.count):
                    byte, lane = run.first + i, run.lane + i
                    source = header[byte] if value is None else _byte(value, byte)
                    table[lane][run.rc] = len(entries[lane]) + 1
                    entries[lane].append(source)
    for lane in range(width):
        if entries[lane]:  # a lane no record reaches stays undriven: it is never given
            parts = [part for entry in reversed([zero, *entries[lane]]) for part in entry]
            blocks.append(lane_select(ConcatSignal(*parts), tuple(table[lane]), rc, lanes[lane]))
    return blocks


def _prefixed(step: Step) -> tuple[str | None, int]:
    """The length or count port of the step a length prefix announces, and its terminator."""
    if isinstance(step, Payload):
        return step.length_port, int(step.terminator)
    assert isinstance(step, Loop), "a length prefix announces a string or a sequence"
    return step.count_port, 0


@block
def lane_pick(bus: SignalLike, index: SignalLike, out: SignalLike) -> Instances:
    """Drive `out` with byte `index` of `bus`."""

    @always_comb
    def pick() -> None:
        for bit in range(8):
            out.next[bit] = bus[8 * int(index) + bit]

    return pick


def payload_bases(plan: Plan) -> tuple[int, ...]:
    """Per step, the position of its first payload piece on every lane's payload bus (0: none)."""
    t = tables(plan)
    bases = [0] * len(plan.steps)
    position = 1
    for pc in t.streams:
        bases[pc] = position
        position += t.pieces[pc]
    return tuple(bases)


@block
def payload_sources(
    plan: Plan, ports: dict[str, SignalLike], index: SignalLike, lanes: list[SignalLike]
) -> Instances:
    """Drive ``lanes[j]`` with byte j of piece `index` of the sub-stream inputs' data.

    Piece ``payload_bases(plan)[pc] + k`` is bytes ``k*W .. k*W+W-1`` of the data input of
    the stream of step ``pc``; piece 0 is zero.
    """
    t = tables(plan)
    width = plan.width
    entries: list[list[SignalLike]] = [[intbv(0)[8:]] for _ in range(width)]
    for pc in t.streams:
        step = plan.steps[pc]
        assert isinstance(step, Payload)
        data = ports[f"{step.stream}_tdata"]
        for piece in range(t.pieces[pc]):
            for lane in range(width):
                entries[lane] += _byte(data, piece * width + lane)
    return [
        lane_pick(ConcatSignal(*reversed(entries[lane])), index, lanes[lane])
        for lane in range(width)
    ]
