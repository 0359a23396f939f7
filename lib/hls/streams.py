"""Width adapters between the converters' sub-streams and a Vitis HLS core's ``ap_fifo`` ports.

A converter's sub-stream carries a beat of ``beat`` bytes holding ``beat // element`` elements
(`rfc.lib.converters.ports.stream_bytes`: a beat is never narrower than an element); an
``hls::stream<T>`` argument with ``ap_fifo`` moves one element at a time: ``dout``/``empty_n``/
``read`` on an input, ``din``/``full_n``/``write`` on an output (Vitis HLS UG1399).

`unpack_beats` hands a subscriber's beats to the core element by element (``tkeep`` marks the
elements of a partial last beat) and takes a beat when its last element is read. `pack_elements`
gathers the core's elements into beats for a publisher, which takes exactly ``length`` elements:
a beat goes out when full or when the elements written reach ``length`` (a length counter, read
as each element is written), and the count starts again for the next message once the beat that
ends it is taken.

These are the building blocks of wiring struct/stream HLS cores into the logic, which rfc does
not do yet (docs/system.md, known limits).
"""

from __future__ import annotations

from typing import Any

from myhdl import Signal, always_comb, always_seq, block, intbv


@block
def unpack_beats(
    clk: Any,
    rst: Any,
    tdata: Any,
    tkeep: Any,
    tvalid: Any,
    tready: Any,
    dout: Any,
    empty_n: Any,
    read: Any,
) -> Any:
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
    clk: Any,
    rst: Any,
    din: Any,
    full_n: Any,
    write: Any,
    length: Any,
    tdata: Any,
    tvalid: Any,
    tready: Any,
) -> Any:
    """Gather elements into beats (the first in the low bytes); send at full or at ``length``."""
    element_bits = len(din)
    per_beat = len(tdata) // element_bits
    fill = Signal(intbv(0, min=0, max=per_beat))
    count = Signal(intbv(0)[len(length) :])
    beat = Signal(intbv(0)[len(tdata) :])
    pending = Signal(bool(0))
    closing = Signal(bool(0))  # the pending beat ends the message

    @always_comb
    def outputs() -> None:
        tdata.next = beat
        tvalid.next = pending
        full_n.next = not pending

    @always_seq(clk.posedge, reset=rst)
    def gather() -> None:
        if pending and tready:
            pending.next = 0
            beat.next = 0
            if closing:
                count.next = 0
        elif write and not pending:
            for k in range(per_beat):
                if fill == k:
                    beat.next[(k + 1) * element_bits : k * element_bits] = din
            count.next = count + 1
            closing.next = count + 1 == length
            if fill == per_beat - 1 or count + 1 == length:
                pending.next = 1
                fill.next = 0
            else:
                fill.next = fill + 1

    return outputs, gather
