"""A register slice: one message between two blocks, every signal it hands on from a register.

The top level puts one on each message handshake between a converter and an accelerator, and
the manager one on each stream it shares with the DMA and the converters, so that no
combinational path runs from one generated block into another (a block's timing is then its
own, docs/performance.md, Timing). It is a skid buffer: ``s_ready``, ``m_valid`` and
the fields all come from flip-flops, it takes a message every cycle while the consumer does,
and it holds one message (and one more in its skid register while the consumer stalls), so a
subscriber can parse the next frame while its consumer still works on the last.
"""

from __future__ import annotations

from dataclasses import dataclass

from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv

from rfc.lib.types import Instances, SignalLike


# Its skid-buffer moves recur in the guards and the manager's mux, on their own registers.
@block
def register_slice(
    clk: SignalLike,
    rst: SignalLike,
    s_data: SignalLike,
    s_valid: SignalLike,
    s_ready: SignalLike,
    m_data: SignalLike,
    m_valid: SignalLike,
    m_ready: SignalLike,
) -> Instances:
    """Pass `s_data` to `m_data` under valid/ready, one message a cycle, all outputs registered."""
    width = len(s_data)
    held = Signal(intbv(0)[width:])
    held_valid = Signal(bool(0))
    skid = Signal(intbv(0)[width:])
    room = Signal(bool(1))  # the skid register is free: kept as a flip-flop, it is `s_ready`

    @always_seq(clk.posedge, reset=rst)
    def step() -> None:
        if m_ready or not held_valid:  # the output register is free this cycle
            if not room:
                held.next = skid
                held_valid.next = True
                room.next = True
            else:
                held.next = s_data
                held_valid.next = s_valid
        elif s_valid and room:  # taken while the consumer stalls: keep it aside
            skid.next = s_data
            room.next = False

    @always_comb
    def drive() -> None:
        s_ready.next = room
        m_valid.next = held_valid
        m_data.next = held

    return step, drive


@block
def slice_body(fields: tuple[tuple[str, int, bool], ...], **ports: SignalLike) -> Instances:
    """`register_slice` over ports ``s_<field>`` → ``m_<field>`` and the two handshakes.

    Args:
        fields: Each field's name, width and whether it is a single-bit (``std_logic``) port.
        **ports: ``clk``, ``rst``, ``s_valid``, ``s_ready``, ``m_valid``, ``m_ready`` and the
            fields' ports.
    """
    total = sum(bits for _, bits, _ in fields)
    if total == 0:  # a message without fields: only the handshake is registered
        s_data = Signal(intbv(0)[1:])
    elif len(fields) == 1:  # a sub-stream's data alone
        s_data = ports[f"s_{fields[0][0]}"]
    else:
        s_data = ConcatSignal(*reversed([ports[f"s_{name}"] for name, _, _ in fields]))
    m_data = Signal(intbv(0)[max(total, 1) :])
    core = register_slice(
        ports["clk"], ports["rst"], s_data, ports["s_valid"], ports["s_ready"], m_data,
        ports["m_valid"], ports["m_ready"],
    )  # fmt: skip
    outputs = []
    low = 0
    for name, bits, single in fields:
        outputs.append(part_of(m_data, low, bits, single, ports[f"m_{name}"]))
        low += bits
    return core, outputs


@dataclass(frozen=True)
class SliceSide:
    """One side of a `parts_slice`: the signals handed on together and their handshake.

    The slices of the manager and the guards take their two sides as these, so that a block
    wrapping a slice names its ports once.

    Attributes:
        parts: The signals handed on together (a stream's tdata, tkeep, tlast …).
        valid: The side's valid.
        ready: The side's ready.
    """

    parts: list[SignalLike]
    valid: SignalLike
    ready: SignalLike


@block
def parts_slice(
    clk: SignalLike, rst: SignalLike, producer: SliceSide, consumer: SliceSide
) -> Instances:
    """`register_slice` over several signals at once (a stream's tdata, tkeep, tlast …).

    Args:
        clk: Clock.
        rst: Synchronous reset.
        producer: At least two signals handed on together; its ready is driven from a
            flip-flop: the slice takes the parts this cycle.
        consumer: One signal per part of the producer's, of its width; its valid is driven
            from a flip-flop: the parts hold a message.
    """
    sources, s_valid, s_ready = producer.parts, producer.valid, producer.ready
    sinks, m_valid, m_ready = consumer.parts, consumer.valid, consumer.ready
    widths = [len(source) for source in sources]
    data = Signal(intbv(0)[sum(widths) :])
    core = register_slice(
        clk, rst, ConcatSignal(*reversed(sources)), s_valid, s_ready, data, m_valid, m_ready
    )
    outputs = []
    low = 0
    for sink, bits in zip(sinks, widths, strict=True):
        outputs.append(part_of(data, low, bits, isinstance(sink.val, bool), sink))
        low += bits
    return core, outputs


@block
def part_of(data: SignalLike, low: int, width: int, single: bool, out: SignalLike) -> Instances:
    """Drive `out` with bits ``low`` … ``low + width - 1`` of `data`."""
    if single:

        @always_comb
        def bit() -> None:
            out.next = data[low]

        return bit

    high = low + width

    @always_comb
    def bits() -> None:
        out.next = data[high:low]

    return bits
