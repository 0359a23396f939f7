"""The manager's registered boundaries: a register slice on every stream it shares.

Everything the manager hands another block comes from a flip-flop: the ``tready`` of the DMA's
MM2S stream and each publisher's grant, the beats and ``tvalid`` of the S2MM stream and of each
subscriber's stream. No combinational path then runs through the manager from one block into
another, and the manager's own paths start and end at its registers (docs/performance.md,
Timing). Each slice (`rfc.lib.slice`) takes a beat every cycle and adds one cycle of latency;
the beats a slice holds let a publisher go on while the scheduler decides.
"""

from __future__ import annotations

from collections.abc import Sequence

from myhdl import Signal, always_comb, block, intbv

from rfc.lib.slice import SliceSide, parts_slice
from rfc.lib.types import Instances, SignalLike


def stream_like(signals: Sequence[SignalLike]) -> list[SignalLike]:
    """Fresh signals of the widths (and kinds) of `signals`, for the other side of a slice."""
    return [
        Signal(bool(0)) if isinstance(s.val, bool) else Signal(intbv(0)[len(s) :]) for s in signals
    ]


# Flat ports, unlike `slice_chain`: its process reads them, and bound from a `SliceSide` they
# would be declared in another order in the VHDL (MyHDL lists a block's signals as Python does).
@block
def routed_slice(
    clk: SignalLike,
    rst: SignalLike,
    sources: list[SignalLike],
    s_valid: SignalLike,
    s_ready: SignalLike,
    sinks: list[SignalLike],
    m_valid: SignalLike,
    m_ready: SignalLike,
) -> Instances:
    """A slice in front of several consumers sharing the sinks: ``s_valid`` says which.

    The consumers' valids travel through the slice with the beat, so each comes from a
    flip-flop: a register that takes ``s_valid`` whenever it takes a beat holds zero when
    there was none.

    Args:
        clk: Clock.
        rst: Synchronous reset.
        sources: The shared beat (tdata, tkeep, tlast).
        s_valid: intbv[N]: the consumer the beat is for (one-hot), or zero.
        s_ready: Bool, driven from a flip-flop: the beat is taken.
        sinks: The beat towards the consumers, one signal per source.
        m_valid: intbv[N] out: the consumer offered the held beat.
        m_ready: intbv[N] in: each consumer's ready.
    """
    any_valid, held_valid, taken = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    core = parts_slice(
        clk,
        rst,
        SliceSide([*sources, s_valid], any_valid, s_ready),
        SliceSide([*sinks, m_valid], held_valid, taken),
    )

    @always_comb
    def offer() -> None:
        any_valid.next = s_valid != 0
        taken.next = (m_valid & m_ready) != 0

    return core, offer


@block
def slice_chain(
    clk: SignalLike, rst: SignalLike, producer: SliceSide, consumer: SliceSide, stages: int
) -> Instances:
    """`stages` slices in a row: room for twice `stages` beats, `stages` cycles of latency."""
    sources, s_valid, s_ready = producer.parts, producer.valid, producer.ready
    sinks, m_valid, m_ready = consumer.parts, consumer.valid, consumer.ready
    parts = []
    for stage in range(stages):
        last = stage == stages - 1
        outputs = sinks if last else stream_like(sources)
        valid = m_valid if last else Signal(bool(0))
        ready = m_ready if last else Signal(bool(0))
        ends = SliceSide(sources, s_valid, s_ready), SliceSide(outputs, valid, ready)
        parts.append(parts_slice(clk, rst, *ends))
        sources, s_valid, s_ready = outputs, valid, ready
    return parts
