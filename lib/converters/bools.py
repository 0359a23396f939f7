"""Bool elements as both converters carry them: one byte each, and true is 1.

A bool sequence travels byte by byte like any uint8 sequence, but rosbags writes true as 1 and
reads any nonzero byte as true; a converter makes each byte of such a step 0 or 1 on its way
through, whatever the other side sent.
"""

from __future__ import annotations

from myhdl import always_comb, block, intbv

from rfc.lib.converters.steps import Plan
from rfc.lib.converters.tables import tables
from rfc.lib.types import Instances, SignalLike


@block
def bool_bytes(plan: Plan, pc: SignalLike, source: SignalLike, out: SignalLike) -> Instances:
    """`out`: the byte lanes of `source`, each made 0 or 1 while step `pc` carries bools."""
    lanes = len(source) // 8
    bool_rom = tables(plan).is_bool

    @always_comb
    def normalize() -> None:
        bools = bool_rom[pc]
        result = intbv(0)[8 * lanes :]
        for lane in range(lanes):
            nonzero = False
            for bit in range(8):
                if source[8 * lane + bit]:
                    nonzero = True
            for bit in range(8):
                if bools == 1:
                    result[8 * lane + bit] = bit == 0 and nonzero
                else:
                    result[8 * lane + bit] = source[8 * lane + bit]
        out.next = result

    return normalize
