"""The subscriber converter: a frame on AXI-Stream in, the message's fields and streams out.

One control process walks the plan (`tables`) through the step walker both converters share
(`walker`) and consumes the byte window (`window`) a record chunk, a payload chunk or a padding
run per cycle. Field registers capture their bytes straight from fixed bus lanes when their
record chunk passes (`fields`); strings and primitive sequences leave through one shared output
register demultiplexed to their sub-streams; each element of a sequence of messages or strings
is handed over on its channel before the next is parsed.

Malformed frames — early ``tlast``, a length beyond its maximum, a CDR string without its NUL,
trailing bytes beyond ROS 2's padding to 4, a wrong CDR encapsulation — raise ``msg_error``,
give their `Reason` on ``error_reason`` and count in ``error_count``. From the first error on,
the parser *aborts*: it stops reading the frame and walks the rest of the plan on zeros
(lengths not yet read become 0), so every stream announced so far still delivers its announced
length and every channel its elements; then it drops the frame's remaining bytes up to
``tlast`` and presents the record with ``msg_error`` set (the system's `drop_gate` takes it).
It never waits for anything but the frame's own bytes and the consumer's ready signals, so it
never hangs.
"""

from __future__ import annotations

from myhdl import Constant, Signal, always_comb, always_seq, block, concat, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.bools import bool_bytes
from rfc.lib.converters.fields import field_captures
from rfc.lib.converters.malformed import Reason
from rfc.lib.converters.outputs import element_handshakes, length_registers, stream_outputs
from rfc.lib.converters.ports import (
    COUNTER_BITS,
    REASON_BITS,
    Side,
    count_bits,
    dma_ports,
    ports_of,
)
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.tables import Kind, tables
from rfc.lib.converters.walker import Walk, step_walker
from rfc.lib.converters.window import byte_window
from rfc.lib.converters.wiring import bits_of, select_bit
from rfc.lib.types import Instances, SignalLike

TRUNCATED, MAXIMUM, TRAILING, ENCODING = (
    int(Reason.TRUNCATED),
    int(Reason.MAXIMUM),
    int(Reason.TRAILING),
    int(Reason.ENCODING),
)
#: The two bytes a little-endian plain-CDR encapsulation header starts with, as a uint16.
CDR_ENCAPSULATION = 0x0100


def subscriber_ports(plan: Plan) -> list[str]:
    """Port names of the subscriber entity, in declaration order."""
    return [p.name for p in (*dma_ports(plan, Side.SUBSCRIBER), *ports_of(plan, Side.SUBSCRIBER))]


@block
def rfc_subscriber(plan: Plan, **ports: SignalLike) -> Instances:
    """The subscriber for `plan`; `ports` holds one signal per name of `subscriber_ports`."""
    t = tables(plan)
    width = plan.width
    clk, rst = ports["clk"], ports["rst"]
    msg_valid, msg_ready, msg_error = ports["msg_valid"], ports["msg_ready"], ports["msg_error"]
    error_count, error_reason = ports["error_count"], ports["error_reason"]
    end_pc = t.end
    payloads = [plan.payload(pc) for pc in t.streams]
    out_bytes = max([width] + [max(width, p.element_size) for p in payloads])
    count_width = count_bits(max([1, *t.maximum]))
    cdr = plan.is_cdr

    # ---- the byte window
    front = Signal(intbv(0)[8 * width :])
    avail = Signal(intbv(0, min=0, max=3 * width + 1))
    ended = Signal(bool(0))
    take = Signal(intbv(0, min=0, max=width + 1))
    release = Signal(bool(0))
    window = byte_window(
        clk,
        rst,
        AxiStream.named(ports, "s_axis"),
        take,
        release,
        front,
        avail,
        ended,
        width,
    )

    # ---- where the walk stands, and the control's own registers and their next values
    walk = Walk.of(plan)
    pc, entered, rem, piece, gap = walk.pc, walk.entered, walk.rem, walk.piece, walk.gap
    rc, size, chars, padding, element_end = walk.proposal()
    go, skip = walk.go, walk.skip
    last4, last4_n = (Signal(intbv(0)[32:]) for _ in range(2))
    abort, abort_n = (Signal(bool(0)) for _ in range(2))
    cause, cause_n = (Signal(intbv(0)[REASON_BITS:]) for _ in range(2))
    trail, trail_n = (Signal(intbv(0)[3:]) for _ in range(2))
    o_data, o_data_n = (Signal(intbv(0)[8 * out_bytes :]) for _ in range(2))
    o_keep, o_keep_n = (Signal(intbv(0)[out_bytes:]) for _ in range(2))
    o_last, o_last_n = (Signal(bool(0)) for _ in range(2))
    o_valid, o_valid_n = (Signal(bool(0)) for _ in range(2))
    o_stream, o_stream_n = (Signal(intbv(0, min=0, max=max(1, len(payloads)))) for _ in range(2))
    errors = Signal(intbv(0)[COUNTER_BITS:])

    # ---- events the control process raises for the data path
    capture = Signal(bool(0))
    lengths = Signal(bool(0))
    count = Signal(intbv(0)[count_width:])
    data = Signal(intbv(0)[8 * width :])
    elements = Signal(intbv(0)[8 * width :])  # `data` with bools made 0 or 1
    finished = Signal(bool(0))
    failed = Signal(bool(0))
    header = Signal(intbv(0)[16:]) if cdr else Constant(intbv(CDR_ENCAPSULATION)[16:])

    # ---- handshakes in from the consumer, selected by the current step
    channel_ready = Signal(bool(1)) if len(plan.channels) > 1 else Constant(bool(1))
    o_ready = Signal(bool(0)) if t.streams else Constant(bool(0))
    readies = [
        ports[f"{c.name}_ready"] if c.index and c.selected else Constant(bool(1))
        for c in plan.channels
    ]
    kind_rom, term_rom, max_rom = t.kind, t.terminator, t.maximum
    stream_rom, selected_rom, pieces_rom = t.stream, t.selected, t.pieces

    @always_comb
    def zero_on_abort() -> None:
        if abort:
            data.next = 0
        else:
            data.next = front

    @always_comb
    def control() -> None:
        kind = kind_rom[pc]
        term = term_rom[pc]
        terminated = term == 1
        maximum = max_rom[pc]
        stream = stream_rom[pc]
        chosen = selected_rom[pc]
        selected = chosen == 1
        parts = pieces_rom[pc]

        moves = False  # the current step goes this cycle (`step_walker`'s go)
        # Each output idle first: shaped like the publisher's and stream_engine's set-ups only.
        abort_n.next = abort
        trail_n.next = trail
        o_data_n.next = o_data
        o_keep_n.next = o_keep
        o_last_n.next = o_last
        o_valid_n.next = o_valid and not o_ready
        o_stream_n.next = o_stream
        take.next = 0
        capture.next = False
        lengths.next = False
        release.next = False
        finished.next = False
        skip.next = False
        count.next = 0
        length = intbv(0)[32:]
        length[:] = last4
        why = 0  # the reason of an abort raised this cycle (`Reason`)
        done = False

        if kind == Kind.RECORD:
            if abort or avail >= size:
                moves = True
                if not abort:
                    take.next = size
                if not padding:
                    capture.next = True
            elif ended:
                abort_n.next = True
                why = TRUNCATED
        elif kind == Kind.PAYLOAD:
            if not entered:
                moves = True
                lengths.next = True
                if (terminated and (length == 0 or length > maximum + 1)) or (
                    not terminated and length > maximum
                ):
                    abort_n.next = True
                    why = MAXIMUM
                    if terminated and length == 0:
                        why = ENCODING
                    skip.next = True
                elif terminated:
                    count.next = length - 1
                else:
                    count.next = length
            elif rem == 0:
                moves = True
            elif padding:
                if abort or avail >= size:
                    moves = True
                    if not abort:
                        take.next = size
                elif ended:
                    abort_n.next = True
                    why = TRUNCATED
            else:
                free = not selected or not o_valid or o_ready
                if (abort or avail >= size) and free:
                    moves = True
                    if not abort:
                        take.next = size
                    if terminated and rem <= width and not abort:
                        for bit in range(8):
                            if front[8 * (int(rem[4:]) - 1) + bit]:
                                abort_n.next = True
                                why = ENCODING
                    if selected and chars > 0:
                        assembled = intbv(0)[8 * out_bytes :]
                        assembled[:] = o_data
                        for lane in range(out_bytes):
                            if lane // width == piece:
                                for bit in range(8):
                                    assembled[8 * lane + bit] = elements[8 * (lane % width) + bit]
                        o_data_n.next = assembled
                        o_stream_n.next = stream
                        if element_end:
                            keep = intbv(0)[out_bytes:]
                            for lane in range(out_bytes):
                                keep[lane] = parts > 1 or lane < chars
                            o_keep_n.next = keep
                            o_last_n.next = rem - term <= width
                            o_valid_n.next = True
                elif ended and avail < rem and not abort:
                    abort_n.next = True
                    why = TRUNCATED
        elif kind == Kind.LOOP:
            moves = True
            lengths.next = True
            if length > maximum:
                abort_n.next = True
                why = MAXIMUM
                skip.next = True
            elif length == 0:
                skip.next = True
            else:
                count.next = length
        elif kind == Kind.NEXT:
            moves = channel_ready and not o_valid
        elif not (ended and avail == 0):
            drained = width
            if avail < width:
                drained = int(avail)
            take.next = drained
            if int(trail) + drained > 7:  # int(): unsigned sums keep the operands' width in VHDL
                trail_n.next = 7
            else:
                trail_n.next = int(trail) + drained
        elif msg_ready and not o_valid:
            moves = True
            finished.next = True
            done = True
            release.next = True
            abort_n.next = False
            trail_n.next = 0
        go.next = moves
        cause_n.next = cause
        if done:
            cause_n.next = 0
        elif why != 0 and not abort:
            cause_n.next = why
        step = 0  # bytes the frame advances by this cycle (zeros when aborted)
        if moves:
            step = int(size)
        shifted = intbv(0)[8 * width + 32 :]
        shifted[:] = concat(data, last4) >> (8 * step)
        last4_n.next = shifted[32:]

    @always_seq(clk.posedge, reset=rst)
    def registers() -> None:
        last4.next = last4_n
        abort.next = abort_n
        cause.next = cause_n
        trail.next = trail_n
        o_data.next = o_data_n
        o_keep.next = o_keep_n
        o_last.next = o_last_n
        o_valid.next = o_valid_n
        o_stream.next = o_stream_n
        if finished and failed:
            errors.next = errors + 1

    allowed = 3 if cdr else 0

    @always_comb
    def cdr_verdict() -> None:
        trailing = trail > (gap & allowed)
        failed.next = abort or trailing or header != CDR_ENCAPSULATION
        if abort:
            error_reason.next = cause
        elif header != CDR_ENCAPSULATION:
            error_reason.next = ENCODING
        elif trailing:
            error_reason.next = TRAILING
        else:
            error_reason.next = 0

    @always_comb
    def ros1_verdict() -> None:  # no encapsulation header to check (nor a constant to compare)
        failed.next = abort or trail != 0
        if abort:
            error_reason.next = cause
        elif trail != 0:
            error_reason.next = TRAILING
        else:
            error_reason.next = 0

    verdict = cdr_verdict if cdr else ros1_verdict

    @always_comb
    def message_handshake() -> None:
        msg_valid.next = pc == end_pc and ended and avail == 0 and not o_valid
        msg_error.next = failed
        error_count.next = errors

    walker = step_walker(plan, clk, rst, walk, count)
    blocks = [window, walker, zero_on_abort, control, registers, verdict, message_handshake]
    blocks.append(bool_bytes(plan, pc, data, elements))
    if len(readies) > 1:
        blocks.append(select_bit(bits_of(readies), t.channel, pc, channel_ready))
    blocks.append(field_captures(plan, ports, clk, rst, capture, rc, data, header))
    blocks.append(length_registers(plan, ports, clk, rst, lengths, pc, count))
    blocks.append(element_handshakes(plan, ports, pc, o_valid, list(walk.loop_counts)))
    blocks.append(stream_outputs(plan, ports, o_data, o_keep, o_last, o_valid, o_stream, o_ready))
    return blocks
