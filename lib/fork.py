"""A handshake fork: one message offered to several consumers, taken once all have taken it.

Fan-out in the data flow (one subscriber feeding two accelerators) shares the message's fields
as wires; only the valid/ready handshake needs this block. Each consumer sees ``valid`` until
it has taken the message; the producer sees ``ready`` in the cycle the last of them takes it.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.wiring import index_bit
from rfc.lib.types import Instances, SignalLike


@block
def handshake_fork(
    clk: SignalLike,
    rst: SignalLike,
    s_valid: SignalLike,
    s_ready: SignalLike,
    m_valid: SignalLike,
    m_ready: SignalLike,
) -> Instances:
    """Fork `s_valid`/`s_ready` to the vectors `m_valid`/`m_ready` (bit i: consumer i)."""
    everyone = (1 << len(m_valid)) - 1
    taken = Signal(intbv(0)[len(m_valid) :])

    @always_comb
    def offer() -> None:
        m_valid.next = 0
        if s_valid:
            m_valid.next = everyone & ~taken
        s_ready.next = (m_ready | taken) == everyone

    @always_seq(clk.posedge, reset=rst)
    def remember() -> None:
        if s_valid and (m_ready | taken) == everyone:
            taken.next = 0
        elif s_valid:
            taken.next = taken | m_ready

    return offer, remember


@block
def fork_body(consumers: int, **ports: SignalLike) -> Instances:
    """`handshake_fork` with one ``m<i>_valid``/``m<i>_ready`` pair of wires per consumer."""
    m_valid = Signal(intbv(0)[consumers:])
    m_ready = ConcatSignal(*(ports[f"m{i}_ready"] for i in reversed(range(consumers))))
    fork = handshake_fork(
        ports["clk"], ports["rst"], ports["s_valid"], ports["s_ready"], m_valid, m_ready
    )
    return fork, [index_bit(m_valid, i, ports[f"m{i}_valid"]) for i in range(consumers)]
