"""Per-input down-counters that load on arrival: LOEDF's deadlines and LST's slack.

Counters are `counter_bits` wide and biased by H = 2^(counter_bits-1), so the unsigned value
H + x stands for x cycles (negative once late) and saturates at 0, never wrapping. Each cycle a
message is pending its counter counts down, except — for LST — on a cycle its beat moves.
The tree's key is the counter's next value with one low bit that is 0 only for the holder, so
the holder keeps the grant on a tie and a new message competes in the cycle it arrives.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from myhdl import Signal, always, always_comb, block, concat, intbv

from rfc.lib.schedulers.statechart import Lines, PolicyHardware
from rfc.lib.types import Instances, SignalLike


@block
def countdown_table(
    lines: Lines, loads: Sequence[int], bits: int, keep_while_moving: bool
) -> Instances:
    """Counters loading `loads[i]` (biased) on arrival; keys = (next value, not holder).

    Args:
        lines: The statechart's signals (clk, rst resetting the counters to 0, arrival, pending,
            grant, hold) and the tree's keys it drives (`bits` + 1 wide).
        loads: Biased value each input's counter takes on arrival.
        bits: Counter width.
        keep_while_moving: The counter of the input whose beat moves does not count (LST).
    """
    n = len(loads)
    load = tuple(int(v) for v in loads)
    clk, rst, keys = lines.clk, lines.rst, lines.keys
    arrival, pending, grant, hold = lines.arrival, lines.pending, lines.grant, lines.hold
    counter = [Signal(intbv(0)[bits:]) for _ in range(n)]
    following = [Signal(intbv(0)[bits:]) for _ in range(n)]

    @always_comb
    def count() -> None:
        for i in range(n):
            if arrival[i]:
                following[i].next = load[i]
            elif pending[i] and counter[i] != 0 and not (keep_while_moving and grant[i]):
                following[i].next = counter[i] - 1
            else:
                following[i].next = counter[i]

    @always(clk.posedge)
    def register() -> None:
        if rst:
            for i in range(n):
                counter[i].next = 0
        else:
            for i in range(n):
                counter[i].next = following[i]

    return count, holder_keys(following, hold, keys), register


@block
def holder_keys(values: list[SignalLike], hold: SignalLike, keys: list[SignalLike]) -> Instances:
    """Drive keys[i] with (values[i], not holder): the holder keeps the grant on a tie."""
    n = len(values)

    @always_comb
    def prioritize() -> None:
        for i in range(n):
            if hold[i]:
                keys[i].next = concat(values[i], False)
            else:
                keys[i].next = concat(values[i], True)

    return prioritize


def countdown_hardware(table: Callable[..., Instances], bits: int) -> PolicyHardware:
    """The statechart parts of a countdown algorithm (LOEDF, LST) whose table is `table`."""
    return PolicyHardware(
        preemptive=True,
        tracks_arrivals=True,
        key_bits=bits + 1,
        modular=False,
        pauses=False,
        table=table,
    )
