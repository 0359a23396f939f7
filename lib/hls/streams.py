"""Width adapters between the converters' sub-streams and a Vitis HLS core's ``ap_fifo`` ports.

A converter's sub-stream carries a beat of ``beat`` bytes holding ``beat // element`` elements
(`rfc.lib.converters.ports.stream_bytes`: a beat is never narrower than an element); an
``hls::stream<T>`` argument with ``ap_fifo`` moves one element at a time: ``dout``/``empty_n``/
``read`` on an input, ``din``/``full_n``/``write`` on an output (Vitis HLS UG1399).

`unpack_beats` hands a subscriber's beats to the core element by element (``tkeep`` marks the
elements of a partial last beat) and takes a beat when its last element is read.

`pack_elements` gathers the core's elements into beats for a publisher, which takes exactly the
length the core sets: a beat goes out when full, and a partial last beat when ``flush`` pulses
(the wrapper pulses it at ``ap_done``, when every element is written). The length need not be
known while the elements are written: Vitis HLS may write the length's ``ap_vld`` port after
the stream.

The wrapper of HLS cores (`rfc.lib.hls.adapter`) instantiates both.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.types import Instances, SignalLike


@block
def unpack_beats(
    clk: SignalLike,
    rst: SignalLike,
    tdata: SignalLike,
    tkeep: SignalLike,
    tvalid: SignalLike,
    tready: SignalLike,
    dout: SignalLike,
    empty_n: SignalLike,
    read: SignalLike,
) -> Instances:
    """Offer the elements of each beat in order, little-endian; pop the beat with its last."""
    element_bits = len(dout)
    element_bytes = element_bits // 8
    per_beat = len(tdata) // element_bits
    index = Signal(intbv(0, min=0, max=per_beat))
    last = Signal(bool(0))

    @always_comb
    def offer() -> None:
        dout.next = 0
        for k in range(per_beat):
            if index == k:
                dout.next = tdata[(k + 1) * element_bits : k * element_bits]
        empty_n.next = tvalid and tkeep[index * element_bytes]

    @always_comb
    def ends() -> None:
        last.next = index == per_beat - 1
        for k in range(per_beat - 1):
            if index == k and not tkeep[(k + 1) * element_bytes]:
                last.next = 1

    @always_comb
    def pop() -> None:
        tready.next = tvalid and read and last

    @always_seq(clk.posedge, reset=rst)
    def advance() -> None:
        if tvalid and read:
            if last:
                index.next = 0
            else:
                index.next = index + 1

    return offer, ends, pop, advance


@block
def pack_elements(
    clk: SignalLike,
    rst: SignalLike,
    din: SignalLike,
    full_n: SignalLike,
    write: SignalLike,
    flush: SignalLike,
    tdata: SignalLike,
    tvalid: SignalLike,
    tready: SignalLike,
) -> Instances:
    """Gather elements into beats (the first in the low bytes); send when full or flushed."""
    element_bits = len(din)
    per_beat = len(tdata) // element_bits
    fill = Signal(intbv(0, min=0, max=per_beat))
    beat = Signal(intbv(0)[len(tdata) :])
    pending = Signal(bool(0))
    flushing = Signal(bool(0))  # a partial beat is to go before any new element

    @always_comb
    def outputs() -> None:
        tdata.next = beat
        tvalid.next = pending
        full_n.next = not pending and not flushing

    @always_seq(clk.posedge, reset=rst)
    def gather() -> None:
        if flush:
            flushing.next = 1
        if pending:
            if tready:
                pending.next = 0
                beat.next = 0
        elif flushing:
            flushing.next = 0
            if fill != 0:
                pending.next = 1
                fill.next = 0
        elif write:
            for k in range(per_beat):
                if fill == k:
                    beat.next[(k + 1) * element_bits : k * element_bits] = din
            if fill == per_beat - 1:
                pending.next = 1
                fill.next = 0
            else:
                fill.next = fill + 1

    return outputs, gather
