"""PL→PS: the scheduler picks a publisher; its payload leaves behind a chunk header.

The publishers' `tvalid` are the scheduler's requests and their `tlast` its task ends; the
scheduler's `offer` names the publisher that holds the channel. For each chunk the mux writes
the 8-byte header (id, flags, the publisher's frame length) and then lets the holder's beats
through: the scheduler's `ready` input is high only then, so its `grant` drives exactly the
holder's `tready`. A chunk's header enters in the cycle the scheduler offers the channel, right
behind the previous chunk's last beat, so chunks leave back to back.

Preemption: when the offer moves to another publisher in the middle of a message, the chunk
ends and the rest of the message follows later in chunks of its own (START clear). AXI-Stream
forbids changing `tlast` once `tvalid` is up, so beats pass through a 2-entry buffer and a beat
leaves with `tlast` low only when its successor is already held: the last beat held can always
carry `tlast` when the chunk has to end. A pause of the scheduler (offer empty, as ROEDF makes
while it recomputes) only waits. END is set in headers of non-preemptive schedulers, whose
chunks always carry whole messages (docs/protocol.md).
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, enum, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.manager.header import FLAG_END, FLAG_START, HEADER_BYTES, BusGeometry
from rfc.lib.schedulers.hardware import scheduler_hardware
from rfc.lib.schedulers.spec import AnySchedulerSpec, CompositionSpec
from rfc.lib.types import Instances, SignalLike


def is_preemptive(spec: AnySchedulerSpec) -> bool:
    """Whether the scheduler (or any scheduler in a composition) may cut a message."""
    if isinstance(spec, CompositionSpec):
        return is_preemptive(spec.parent) or any(is_preemptive(c) for c in spec.children)
    return spec.algorithm.preemptive


@block
def chunk_mux(
    clk: SignalLike,
    rst: SignalLike,
    s: AxiStream,
    s_length: SignalLike,
    m: AxiStream,
    width: int,
    scheduler: AnySchedulerSpec,
) -> Instances:
    """Multiplex `publishers` converters onto the PL→PS DMA stream through a scheduler.

    Args:
        clk: Clock.
        rst: Synchronous reset, active high.
        s: The publishers' streams in, publisher i's ``tdata`` in bits [(i+1)*width, i*width)
            and its ``tkeep`` likewise; ``tvalid`` (requests), ``tready`` (the scheduler's
            grant) and ``tlast`` (message ends) one bit per publisher.
        s_length: intbv[publishers*32] in: each publisher's frame length in bytes, valid
            whenever its `tvalid` is high and stable until its `tlast` beat.
        m: The stream out to the DMA (S2MM), `width` bits a beat.
        width: Bus width in bits (8, 32, 64).
        scheduler: The scheduler, one input per publisher (its `n` is the publisher count).
    """
    s_tdata, s_tkeep, s_tvalid, s_tready, s_tlast = s.signals()
    m_tdata, m_tkeep, m_tvalid, m_tready, m_tlast = m.signals()
    geometry = BusGeometry(width)
    lanes = geometry.lanes
    header_beats = geometry.header_beats
    n = scheduler.n
    preemptive = is_preemptive(scheduler)
    flags_whole = FLAG_START | FLAG_END
    t_state = enum("IDLE", "HEADER", "PAYLOAD")  # no process may share these names

    ready = Signal(bool(0))
    offer = Signal(intbv(0)[n:])
    grant = Signal(intbv(0)[n:])
    state = Signal(t_state.IDLE)
    owner = Signal(intbv(0, min=0, max=max(n, 2)))
    offered = Signal(intbv(0, min=0, max=max(n, 2)))
    header = Signal(intbv(0)[8 * HEADER_BYTES :])
    opening = Signal(intbv(0)[8 * HEADER_BYTES :])
    beat = Signal(intbv(0, min=0, max=header_beats + 1))
    in_progress = Signal(intbv(0)[n:])
    # The 2-entry buffer, head first; an entry's `last` says it ends its chunk.
    count = Signal(intbv(0, min=0, max=3))
    head_data = Signal(intbv(0)[width:])
    head_keep = Signal(intbv(0)[lanes:])
    head_last = Signal(bool(0))
    tail_data = Signal(intbv(0)[width:])
    tail_keep = Signal(intbv(0)[lanes:])
    tail_last = Signal(bool(0))
    # The holder's lanes, and what enters the buffer this cycle.
    owner_data = Signal(intbv(0)[width:])
    owner_keep = Signal(intbv(0)[lanes:])
    owner_last = Signal(bool(0))
    owner_offered = Signal(bool(0))
    switch = Signal(bool(0))
    space = Signal(bool(0))
    leaving = Signal(bool(0))
    out_valid = Signal(bool(0))

    arbiter = scheduler_hardware(clk, rst, s_tvalid, s_tlast, ready, offer, grant, scheduler)

    @always_comb
    def select_holder() -> None:
        data = intbv(0)[width:]
        keep = intbv(0)[lanes:]
        for index in range(n):
            if owner == index:
                data[:] = s_tdata[(index + 1) * width : index * width]
                keep[:] = s_tkeep[(index + 1) * lanes : index * lanes]
        owner_data.next = data
        owner_keep.next = keep
        owner_last.next = s_tlast[owner]
        owner_offered.next = offer[owner]
        switch.next = offer != 0 and not offer[owner]

    @always_comb
    def find_offered() -> None:
        chosen = 0
        for index in range(n):
            if offer[index]:
                chosen = index
        offered.next = chosen

    @always_comb
    def open_chunk() -> None:
        # The header of a chunk of the offered publisher: id, flags, its frame length.
        flags = intbv(0)[16:]
        if preemptive:
            if not in_progress[offered]:
                flags[:] = FLAG_START
        else:
            flags[:] = flags_whole
        assembled = intbv(0)[8 * HEADER_BYTES :]
        assembled[16:0] = offered
        assembled[32:16] = flags
        for index in range(n):
            if offered == index:
                assembled[64:32] = s_length[(index + 1) * 32 : index * 32]
        opening.next = assembled

    @always_comb
    def present() -> None:
        # A beat leaves once it is known to end its chunk or its successor is held: the
        # last beat held can then always carry `tlast` when a preemption ends the chunk.
        valid = count == 2 or (count == 1 and head_last)
        out_valid.next = valid
        leaving.next = valid and m_tready
        space.next = count < 2 or (valid and m_tready)

    @always_comb
    def drive_outputs() -> None:
        m_tvalid.next = out_valid
        m_tlast.next = head_last
        m_tdata.next = head_data
        m_tkeep.next = head_keep
        ready.next = state == t_state.PAYLOAD and owner_offered and space
        s_tready.next = grant

    @always_seq(clk.posedge, reset=rst)
    def sequence() -> None:
        # What enters the buffer this cycle, if anything, and whether the chunk ends on the
        # youngest beat already held (a preemption, or a null last beat folded onto it).
        enter = False
        enter_last = False
        ending = False
        enter_data = intbv(0)[width:]
        enter_keep = intbv(0)[lanes:]
        if state == t_state.IDLE:
            # The next chunk opens as soon as the scheduler offers, behind the last one's end.
            if offer != 0 and space:
                owner.next = offered
                header.next = opening
                enter = True
                enter_data[:] = opening[width:0]
                enter_keep[:] = 2**lanes - 1
                for index in range(n):  # constant bit indices: no memory to infer
                    if offered == index:
                        in_progress.next[index] = True
                if header_beats == 1:
                    state.next = t_state.PAYLOAD
                else:
                    beat.next = 1
                    state.next = t_state.HEADER
        elif state == t_state.HEADER:
            if space:
                enter = True
                for index in range(1, header_beats):
                    if beat == index:
                        enter_data[:] = header[(index + 1) * width : index * width]
                enter_keep[:] = 2**lanes - 1
                if beat == header_beats - 1:
                    state.next = t_state.PAYLOAD
                beat.next = beat + 1
        elif grant != 0:
            if owner_last:
                state.next = t_state.IDLE
                for index in range(n):
                    if owner == index:
                        in_progress.next[index] = False
            # A null beat (tkeep empty) only carries tlast: it folds onto the held beat.
            if owner_keep != 0 or not owner_last:
                enter = True
                enter_last = bool(owner_last)
                enter_data[:] = owner_data
                enter_keep[:] = owner_keep
            else:
                ending = True
        elif switch:
            ending = True
            state.next = t_state.IDLE

        # The buffer: the head leaves and the tail moves up; the entering beat joins behind
        # what stays, and a chunk's end with nothing entering marks the youngest beat held.
        # (Beat moves alike in shape to the slice's and the prefix guard's: other registers.)
        if leaving and count == 2:
            head_data.next = tail_data
            head_keep.next = tail_keep
            head_last.next = tail_last or ending
        if enter:
            if count == 0 or (leaving and count == 1):
                head_data.next = enter_data
                head_keep.next = enter_keep
                head_last.next = enter_last
            else:
                tail_data.next = enter_data
                tail_keep.next = enter_keep
                tail_last.next = enter_last
            if not leaving:
                count.next = count + 1
        elif leaving:
            count.next = count - 1
        elif ending:
            if count == 2:
                tail_last.next = True
            else:
                head_last.next = True

    return arbiter, select_holder, find_offered, open_chunk, present, drive_outputs, sequence
