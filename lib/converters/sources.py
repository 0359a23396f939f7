"""Where each byte a publisher sends comes from: per-lane multiplexers over fixed sources.

Record chunk ``rc`` puts, on bus lane ``j``, one byte known at compile time: a byte of a field
input, of a length prefix, of the CDR header, or a zero (padding, excluded fields). So each
lane gets, per bit, a plane of what that bit is at each ``rc`` and selects it by ``rc``: eight
multiplexers as wide as the number of chunks, not as the message. Payload bytes work the same
way with the sub-streams' data inputs, indexed by stream and piece.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Signal, always_comb, block, intbv

from rfc.lib.converters.frame_length import accumulate
from rfc.lib.converters.steps import Loop, Payload, Plan, SlotRole, Step
from rfc.lib.converters.tables import pieces, tables
from rfc.lib.types import Instances, SignalLike

#: The four bytes of a little-endian plain-CDR encapsulation header.
CDR_HEADER = (0x00, 0x01, 0x00, 0x00)


@block
def lane_bits(planes: tuple[SignalLike, ...], index: SignalLike, out: SignalLike) -> Instances:
    """Drive bit b of `out` with bit `index` of ``planes[b]``.

    One multiplexer per bit, as wide as a plane, selected by `index` itself: no table lookup
    and no arithmetic on the index, so synthesis sees eight narrow multiplexers where a byte
    picked at ``8 * table[index]`` of a byte bus is eight shifters as wide as the whole bus
    (minutes and gigabytes of Yosys on a large message).
    """
    p0, p1, p2, p3, p4, p5, p6, p7 = planes

    @always_comb
    def select() -> None:
        out.next[0] = p0[index]
        out.next[1] = p1[index]
        out.next[2] = p2[index]
        out.next[3] = p3[index]
        out.next[4] = p4[index]
        out.next[5] = p5[index]
        out.next[6] = p6[index]
        out.next[7] = p7[index]

    return select


def _bits(source: SignalLike | int | None, index: int) -> list[SignalLike | intbv]:
    """Bits 0 to 7 of byte `index` of a field, a constant or (None) the CDR header.

    Each bit is a one-bit slice of the field's signal or a one-bit constant: MyHDL converts a
    `ConcatSignal` nested in another as its initial value, so every plane is built flat.
    """
    if source is None or isinstance(source, int):
        value = CDR_HEADER[index] if source is None else source >> (8 * index)
        return [intbv((value >> bit) & 1)[1:] for bit in range(8)]
    if len(source) == 1:  # a bool: 0 or 1
        return [source, *(intbv(0)[1:] for _ in range(7))]
    return [source(8 * index + bit) for bit in range(8)]


@block
def record_sources(
    plan: Plan, ports: dict[str, SignalLike], rc: SignalLike, lanes: list[SignalLike]
) -> Instances:
    """Drive ``lanes[j]`` with the byte record chunk `rc` sends on lane j."""
    t = tables(plan)
    width = plan.width
    zero = [intbv(0)[1:] for _ in range(8)]
    # Per lane, per rc, the bits that lane carries then.
    chunk_bits = [[zero] * t.record_chunks for _ in range(width)]
    blocks = []
    for pc, step in plan.records():
        for slot in step.slots:
            value: SignalLike | int | None
            if slot.role is SlotRole.ENCAPSULATION:
                value = None
            elif slot.role is SlotRole.LENGTH:
                port, terminator = _prefixed(plan.steps[pc + 1])
                if port:
                    value = Signal(intbv(0)[32:])
                    # the uint32 a prefix carries: the count, plus the NUL of a CDR string
                    blocks.append(accumulate(ports[port], terminator, value))
                elif terminator:
                    value = terminator  # an empty CDR string: its NUL
                else:
                    continue
            elif slot.port:
                value = ports[slot.port]
            else:
                continue
            for run in pieces(slot, t.base[pc], width):
                for i in range(run.count):
                    chunk_bits[run.lane + i][run.rc] = _bits(value, run.first + i)
    # In a record, rc is below the record chunks: its low bits select, and the high ones only
    # count the chunks of payloads, whose cycles send no record byte.
    index_bits = max(1, (t.record_chunks - 1).bit_length())
    index = rc(index_bits, 0) if index_bits < len(rc) else rc
    for lane in range(width):
        if any(bits is not zero for bits in chunk_bits[lane]):  # else never given: undriven
            sent = chunk_bits[lane]
            # Every value the index can hold has an input (an index out of a VHDL vector's
            # range stops a simulation); beyond the records, where nothing is sent, the last
            # chunk's bits, as a ROM's `others` gives, keep the multiplexer small.
            planes = _planes(sent + [sent[-1]] * ((1 << index_bits) - t.record_chunks))
            blocks.append(lane_bits(planes, index, lanes[lane]))
    return blocks


def _prefixed(step: Step) -> tuple[str | None, int]:
    """The length or count port of the step a length prefix announces, and its terminator."""
    if isinstance(step, Payload):
        return step.length_port, int(step.terminator)
    assert isinstance(step, Loop), "a length prefix announces a string or a sequence"
    return step.count_port, 0


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
    zero = [intbv(0)[1:] for _ in range(8)]
    # Per lane, per value of the index's bits, the bits that lane carries then.
    piece_bits = [[zero] * (1 << len(index)) for _ in range(width)]
    bases = payload_bases(plan)
    for pc in t.streams:
        step = plan.steps[pc]
        assert isinstance(step, Payload)
        data = ports[f"{step.stream}_tdata"]
        for piece in range(t.pieces[pc]):
            for lane in range(width):
                piece_bits[lane][bases[pc] + piece] = _bits(data, piece * width + lane)
    return [lane_bits(_planes(piece_bits[lane]), index, lanes[lane]) for lane in range(width)]


def _planes(bits_by_index: list[list[SignalLike | intbv]]) -> tuple[SignalLike, ...]:
    """Bit b of every entry, entry 0 lowest: the eight inputs of a `lane_bits`."""
    return tuple(ConcatSignal(*reversed([bits[bit] for bits in bits_by_index])) for bit in range(8))
