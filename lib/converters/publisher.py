"""The publisher converter: the accelerator's fields and streams in, a frame on AXI-Stream out.

It walks the same plan as the subscriber, through the same step walker (`walker`), and gives
the byte packer (`packer`) a record chunk, a payload chunk or padding per cycle. Record bytes
come from fixed sources per lane (`sources`): field inputs, length prefixes computed from the
length inputs, the CDR header, zeros for excluded fields and padding. Strings and sequences are
pulled from their sub-streams when their turn comes; each element of a sequence of messages is
taken from its channel when its first byte is due and acknowledged when its last one is out.

The frame's length is known before the first beat: folded at compile time for a fixed-size
message, computed by the frame-length circuit (`frame_length`) from the length inputs
otherwise, and counted through a frame buffer (`frame_buffer`) when the plan is
store-and-forward. ``frame_length`` holds it from the first beat to the last.

Behind a record-first producer (`Plan.streamed_last`) the frame starts at the first beat of
the message's last stream, which goes straight through; the message is taken at the end,
once its ``valid`` says the producer has handed everything over. A stream that ends early is
padded with zeros to its announced length, beats beyond it are taken and dropped; either
counts one in ``error_count``. The earlier strings come through FIFOs (`buffers`), whose
``held`` emptiness tells the same for them: the producer has gone on to the last stream (or
finished) and a FIFO is empty while its stream still owes beats.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Constant, Signal, always_comb, always_seq, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.bools import bool_bytes
from rfc.lib.converters.frame_buffer import frame_buffer
from rfc.lib.converters.frame_length import frame_length_circuit
from rfc.lib.converters.packer import byte_packer
from rfc.lib.converters.ports import COUNTER_BITS, Side, dma_ports, ports_of
from rfc.lib.converters.sources import payload_bases, payload_sources, record_sources
from rfc.lib.converters.steps import End, Loop, Next, Payload, Plan, Record
from rfc.lib.converters.tables import Kind, tables
from rfc.lib.converters.walker import Walk, step_walker
from rfc.lib.converters.wiring import bits_of, follow, select_bit
from rfc.lib.slice import register_slice
from rfc.lib.types import Instances, SignalLike
from rfc.messages.codec import default_values, encode


def publisher_ports(plan: Plan) -> list[str]:
    """Port names of the publisher entity, in declaration order."""
    return [p.name for p in (*dma_ports(plan, Side.PUBLISHER), *ports_of(plan, Side.PUBLISHER))]


def _owners(plan: Plan) -> tuple[int, ...]:
    """Per step, the channel whose inputs it reads (0: the message)."""
    owners = []
    for step in plan.steps:
        if isinstance(step, Record | Payload | Loop | Next):
            owners.append(step.channel)
        else:
            assert isinstance(step, End)
            owners.append(0)
    return tuple(owners)


def _length_inputs(plan: Plan) -> tuple[list[str], tuple[int, ...]]:
    """The length and count input ports, and per step the position of its own (0: none)."""
    index = [0] * len(plan.steps)
    for position, (at, _) in enumerate(plan.length_ports(), start=1):
        index[at] = position
    return [name for _, name in plan.length_ports()], tuple(index)


@block
def rfc_publisher(
    plan: Plan, held: dict[str, SignalLike] | None = None, **ports: SignalLike
) -> Instances:
    """The publisher for `plan`; `ports` holds one signal per name of `publisher_ports`.

    `held`: behind a record-first producer, per stream that comes through a FIFO, a signal
    high while that FIFO holds nothing.
    """
    t = tables(plan)
    width = plan.width
    clk, rst = ports["clk"], ports["rst"]
    msg_valid, msg_ready = ports["msg_valid"], ports["msg_ready"]
    buffered = plan.store_and_forward
    bases = payload_bases(plan)
    owner_rom = _owners(plan)
    length_names, length_rom = _length_inputs(plan)
    kind_rom = t.kind

    walk = Walk.of(plan)
    pc, entered, rem, piece = walk.pc, walk.entered, walk.rem, walk.piece
    rc, size, chars, padding, element_end = walk.proposal()
    go, skip = walk.go, walk.skip
    active, active_n = (Signal(bool(0)) for _ in range(2))
    give = Signal(intbv(0, min=0, max=width + 1))
    data = Signal(intbv(0)[8 * width :])
    room, idle = Signal(bool(0)), Signal(bool(0))
    start, flush, commit = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    count = Signal(intbv(0)[32:])
    record_lanes = [Signal(intbv(0)[8:]) for _ in range(width)]
    record_bytes = ConcatSignal(*reversed(record_lanes)) if width > 1 else record_lanes[0]
    piece_index = Signal(intbv(0, min=0, max=max(2, max(bases) + max(t.pieces) + 1)))
    payload_lanes = [Signal(intbv(0)[8:]) for _ in range(width)]
    payload_bytes = ConcatSignal(*reversed(payload_lanes)) if width > 1 else payload_lanes[0]
    elements = Signal(intbv(0)[8 * width :])
    fixed = plan.layout.fixed_size
    if fixed is None and not length_names:  # every string and sequence stays empty: one size
        fixed = len(encode(plan.layout, default_values(plan.layout)))
    frame_total = Signal(intbv(0)[COUNTER_BITS:]) if fixed is None else Constant(intbv(fixed)[32:])
    frame_length = ports["frame_length"]
    written = Signal(intbv(0)[COUNTER_BITS:])
    p_data = Signal(intbv(0)[8 * width :])
    p_keep = Signal(intbv(0)[width:])
    p_valid, p_last = Signal(bool(0)), Signal(bool(0))
    p_ready = Constant(bool(1))  # the frame buffer takes every beat
    busy = Signal(bool(0)) if buffered else Constant(bool(0))
    through = plan.streamed_last
    streaming = through is not None
    through_at = through or 0
    skid = []
    pending = Constant(bool(0))  # a beat of the streamed-through stream waits at the port
    through_valid = Constant(bool(0))  # a beat of it waits at the port or in the skid
    if through is not None:
        ends = [f"{plan.payload(through).stream}_{end}" for end in ("tdata", "tvalid", "tready")]
        outer = [ports[name] for name in ends]
        inner = [Signal(intbv(0)[len(outer[0]) :]), Signal(bool(0)), Signal(bool(0))]
        pending, through_valid = outer[1], Signal(bool(0))
        skid.append(skid_through(clk, rst, outer, inner, through_valid))
        ports = {**ports, **dict(zip(ends, inner, strict=True))}
    faulty, faulty_n, drain = (Signal(bool(0)) for _ in range(3))
    held = held or {}
    held_table = [0] * len(plan.steps)
    empties = [Constant(bool(0))]
    for at, step in enumerate(plan.steps):
        if isinstance(step, Payload) and step.stream in held:
            held_table[at] = len(empties)
            empties.append(held[step.stream])
    gone = Signal(bool(0)) if held else Constant(bool(0))  # the current step's FIFO is empty
    leftover = Signal(bool(0)) if held else Constant(bool(0))  # some FIFO still holds beats
    mismatches = Signal(intbv(0)[COUNTER_BITS:])

    channel_valids = [
        ports[f"{c.name}_valid"] if c.index and c.selected else Constant(bool(1))
        for c in plan.channels
    ]
    owner_valid = Signal(bool(1)) if len(channel_valids) > 1 else Constant(bool(1))
    lengths = [Constant(intbv(0)[32:])] + [ports[name] for name in length_names]
    length_bus = (
        ConcatSignal(*[part for s in reversed(lengths) for part in _widened(s)])
        if length_names
        else lengths[0]
    )
    streams = [plan.payload(at) for at in t.streams]
    stream_valid = Signal(bool(0)) if streams else Constant(bool(0))
    stream_take = Signal(bool(0))

    @always_comb
    def control() -> None:
        kind = kind_rom[pc]
        slot = length_rom[pc]
        payload_base = bases[pc]

        # Each output idle first: the subscriber's control starts alike, with other outputs.
        active_n.next = active
        give.next = 0
        data.next = 0
        start.next = False
        flush.next = False
        commit.next = False
        stream_take.next = False
        msg_ready.next = False
        drain.next = False
        faulty_n.next = faulty
        go.next = False
        skip.next = False
        piece_index.next = payload_base + piece
        value = intbv(0)[32:]
        for bit in range(32):
            value[bit] = length_bus[32 * slot + bit]
        count.next = value

        running = bool(active)
        if not active and (msg_valid or through_valid) and idle and not busy:
            start.next = True
            active_n.next = True
            faulty_n.next = False
            running = True
        # the producer is done while the streamed-through stream still owes bytes
        finished = msg_valid and pc == through_at and not pending
        moved_on = gone and (msg_valid or through_valid)
        ended = streaming and (finished or moved_on) and not stream_valid
        if running and owner_valid:
            if kind == Kind.RECORD:
                if room:
                    go.next = True
                    give.next = size
                    if not padding:
                        data.next = record_bytes
            elif kind == Kind.PAYLOAD:
                if not entered or rem == 0:
                    go.next = True
                elif padding:
                    if room:
                        go.next = True
                        give.next = size
                elif room and (chars == 0 or stream_valid or ended):
                    go.next = True
                    give.next = size
                    if ended and chars > 0:
                        faulty_n.next = True
                    stream_take.next = element_end and chars > 0 and not ended
                    masked = intbv(0)[8 * width :]
                    for lane in range(width):
                        if lane < chars and not ended:
                            for bit in range(8):
                                masked[8 * lane + bit] = elements[8 * lane + bit]
                    data.next = masked
            elif kind == Kind.LOOP:
                go.next = True
                skip.next = value == 0
            elif kind == Kind.NEXT:
                go.next = True
            else:  # the End: the message is taken once its frame is out
                done = not streaming and not buffered
                if streaming:
                    if through_valid or leftover:  # beats beyond the announced length
                        drain.next = True
                        faulty_n.next = True
                    else:
                        done = bool(msg_valid)
                elif buffered:
                    flush.next = True
                    done = idle and not p_valid
                    commit.next = done
                if done:
                    msg_ready.next = True
                    go.next = True
                    active_n.next = False

    @always_seq(clk.posedge, reset=rst)
    def registers() -> None:
        active.next = active_n
        if start:
            written.next = give
        else:
            written.next = written + give
        if start and not buffered:
            frame_length.next = frame_total
        elif commit:
            frame_length.next = written
        if streaming:
            faulty.next = faulty_n
            if msg_ready and faulty_n:
                mismatches.next = mismatches + 1

    walker = step_walker(plan, clk, rst, walk, count)
    blocks = [walker, control, registers, record_sources(plan, ports, rc, record_lanes), *skid]
    if len(channel_valids) > 1:
        blocks.append(select_bit(bits_of(channel_valids), owner_rom, pc, owner_valid))
    blocks.append(channel_readies(plan, ports, pc, walk.next_element))
    if streams:
        blocks.append(payload_sources(plan, ports, piece_index, payload_lanes))
        blocks.append(bool_bytes(plan, pc, payload_bytes, elements))
        blocks.append(stream_handshakes(plan, ports, pc, stream_take, stream_valid, drain))
    if streaming:
        blocks.append(follow(mismatches, ports["error_count"]))
    if held:
        blocks.append(select_bit(bits_of(empties), tuple(held_table), pc, gone))
        blocks.append(anything_left(bits_of(empties[1:]), leftover))
    if fixed is None and not buffered:
        counts = {name: ports[name] for name in length_names}
        blocks.append(frame_length_circuit(plan, counts, frame_total))
    m_axis = AxiStream.named(ports, "m_axis")
    if not buffered:
        blocks.append(
            byte_packer(clk, rst, give, data, room, start, frame_total, flush, idle, m_axis, width)
        )
        return blocks
    largest = Constant(intbv(2**COUNTER_BITS - 1)[COUNTER_BITS:])
    packed = AxiStream(p_data, p_keep, p_valid, p_ready, p_last)
    blocks.append(
        byte_packer(clk, rst, give, data, room, start, largest, flush, idle, packed, width)
    )
    depth = -(-plan.limits.frame // width)
    errors = ports["error_count"]
    blocks.append(
        frame_buffer(clk, rst, p_data, p_valid, commit, written, busy, errors, m_axis, width, depth)
    )
    return blocks


@block
def skid_through(
    clk: SignalLike,
    rst: SignalLike,
    outer: list[SignalLike],
    inner: list[SignalLike],
    waiting: SignalLike,
) -> Instances:
    """A register slice from the streamed-through stream's port to the publisher's side of it.

    Its ``tready`` then comes from a flip-flop, so no path runs from the publisher's frame
    logic back into the producer. `outer` and `inner` are ``tdata``, ``tvalid``, ``tready`` of
    the port and of the publisher's side; `waiting` is high while a beat waits at either, so
    the stream has ended only once both are empty (a producer may raise ``msg_valid`` with its
    last beat).
    """
    outer_valid, inner_valid = outer[1], inner[1]

    @always_comb
    def either() -> None:
        waiting.next = outer_valid or inner_valid

    return register_slice(clk, rst, *outer, *inner), either


def _widened(signal: SignalLike) -> list[SignalLike]:
    """A length input zero-extended to 32 bits: parts of the (flat) bus the control reads."""
    if len(signal) >= 32:
        return [signal]
    return [intbv(0)[32 - len(signal) :], signal]


@block
def step_ready(done: SignalLike, pc: SignalLike, at: int, ready: SignalLike) -> Instances:
    """Acknowledge a channel's element or a sub-stream's beat when step `at` is `done` with it."""

    @always_comb
    def acknowledge() -> None:
        ready.next = done and pc == at

    return acknowledge


@block
def channel_readies(
    plan: Plan, ports: dict[str, SignalLike], pc: SignalLike, next_element: SignalLike
) -> Instances:
    """One `step_ready` per selected element channel: at its Next step."""
    blocks = []
    for at, step in enumerate(plan.steps):
        if isinstance(step, Next) and plan.channels[step.channel].selected:
            ready = ports[f"{plan.channels[step.channel].name}_ready"]
            blocks.append(step_ready(next_element, pc, at, ready))
    return blocks


# Compares with all ones where the manager's `spread_bit` drives them: another circuit.
@block
def anything_left(empties: SignalLike, left: SignalLike) -> Instances:
    """`left` while any of the FIFOs whose `empties` bits these are holds a beat."""
    full = 2 ** len(empties) - 1

    @always_comb
    def check() -> None:
        left.next = empties != full

    return check


# Shaped like the guards' `buffer_addresses`: there an address clamp, here a handshake.
@block
def draining_ready(
    take: SignalLike, pc: SignalLike, at: int, drain: SignalLike, ready: SignalLike
) -> Instances:
    """`step_ready`, and every beat while `drain`: the streamed-through stream's extra beats."""

    @always_comb
    def acknowledge() -> None:
        ready.next = (take and pc == at) or drain

    return acknowledge


# A plan, its ports and the control's signals, as every part of a converter takes them.
@block
def stream_handshakes(
    plan: Plan,
    ports: dict[str, SignalLike],
    pc: SignalLike,
    take: SignalLike,
    valid: SignalLike,
    drain: SignalLike,
) -> Instances:
    """Sub-stream readies, and `valid`: the tvalid of the current step's sub-stream."""
    t = tables(plan)
    blocks = []
    valids = []
    table = [0] * len(plan.steps)
    for index, at in enumerate(t.streams):
        stream = plan.payload(at)
        ready = ports[f"{stream.stream}_tready"]
        if plan.streamed_last is not None and stream.channel == 0:
            blocks.append(draining_ready(take, pc, at, drain, ready))
        else:
            blocks.append(step_ready(take, pc, at, ready))
        valids.append(ports[f"{stream.stream}_tvalid"])
        table[at] = index
    if len(valids) > 1:
        blocks.append(select_bit(bits_of(valids), tuple(table), pc, valid))
    else:
        blocks.append(follow(valids[0], valid))
    return blocks
