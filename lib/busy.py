"""Whether a block of the logic is still working on a message: the top level's ``busy`` bits.

A simulated replay calls the logic idle after a quiet window without DMA traffic; an
accelerator that computes longer than that without a transfer would lose its outputs. Each
watch follows one block's message handshakes and says when it still owes an answer:

* it is busy while any input offers a message (``valid`` high, taken or not: a stage that
  streams its input holds ``valid`` until it answers), and
* from the cycle it takes a message on any input until each of its outputs has completed one
  message since (a handshake with ``last`` high: the message handshake of an accelerator, the
  end of a frame of a publisher). Outputs completed in the very cycle it takes the message
  count for it: a block that lets its input go as it answers takes and answers at once.

A block that answers an input with no message on some output stays busy until its next input;
a pipelined block holding several messages counts as finished with the oldest one's outputs.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.wiring import bits_of
from rfc.lib.types import Instances, SignalLike


# Its ports are the handshake names of `rfc.lib.arith.pipeline`, its logic its own.
@block
def busy_watch(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    out_last: SignalLike,
    busy: SignalLike,
) -> Instances:
    """Drive `busy` from a block's input handshakes (vectors, bit i: input i) and its outputs'."""
    everyone = (1 << len(out_valid)) - 1
    owing = Signal(bool(0))
    emitted = Signal(intbv(0)[len(out_valid) :])
    ended = Signal(intbv(0)[len(out_valid) :])
    taken = Signal(bool(0))

    @always_comb
    def handshakes() -> None:
        ended.next = out_valid & out_ready & out_last
        taken.next = (in_valid & in_ready) != 0

    @always_comb
    def report() -> None:
        busy.next = owing or in_valid != 0

    @always_seq(clk.posedge, reset=rst)
    def follow() -> None:
        if taken and ended == everyone:
            owing.next = False
            emitted.next = 0
        elif taken:
            owing.next = True
            emitted.next = ended
        elif owing and (emitted | ended) == everyone:
            owing.next = False
            emitted.next = 0
        elif owing:
            emitted.next = emitted | ended

    return handshakes, report, follow


@block
def busy_body(inputs: int, outputs: int, **ports: SignalLike) -> Instances:
    """`busy_watch` with wires ``in<i>_valid``/``in<i>_ready`` and ``out<j>_valid/ready/last``."""

    def wires(side: str, count: int, signal: str) -> SignalLike:
        return bits_of([ports[f"{side}{i}_{signal}"] for i in range(count)])

    return busy_watch(
        ports["clk"],
        ports["rst"],
        wires("in", inputs, "valid"),
        wires("in", inputs, "ready"),
        wires("out", outputs, "valid"),
        wires("out", outputs, "ready"),
        wires("out", outputs, "last"),
        ports["busy"],
    )
