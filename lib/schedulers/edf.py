"""EDF, two ways: LOEDF (latency-optimized) and ROEDF (resource-optimized).

LOEDF keeps a saturating down-counter per input (cycles to the deadline, loaded with D_i - 1 on
arrival) and merges Compute Condition into Set Grant: the tree compares the counters' next
values on every cycle, so a request is granted on the next cycle and a more urgent arrival
preempts at once.

ROEDF keeps no per-input arithmetic. A free-running timer and one shared adder turn a waiting
request into an absolute deadline (timer + D_i, from a ROM of the D_i), one request per cycle,
lowest index first; while any request waits to be registered the statechart stays in COMPUTE
and withholds the grant (the holder is paused). Leaving COMPUTE, Set Grant compares the
registered deadlines on the wrapping timer's circle. Fewer LUTs, paid for in grant latency:
two cycles for a lone request, one more per request registered in the same burst.
"""

from __future__ import annotations

from myhdl import Signal, always, always_comb, block, intbv, modbv

from rfc.lib.schedulers.countdown import countdown_hardware, countdown_table, holder_keys
from rfc.lib.schedulers.priority_tree import index_bits, priority_tree
from rfc.lib.schedulers.registry import policy
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.lib.schedulers.statechart import Lines, PolicyHardware
from rfc.lib.types import Instances


@block
def loedf_table(lines: Lines, spec: SchedulerSpec) -> Instances:
    """Deadline counters: load D_i - 1 (biased) on arrival, count down while pending."""
    bias = 1 << (spec.counter_bits - 1)
    loads = [d - 1 + bias for d in spec.deadline]
    return countdown_table(lines, loads, spec.counter_bits, False)


@policy(Algorithm.LOEDF)
def loedf_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """The statechart parts of LOEDF."""
    return countdown_hardware(loedf_table, spec.counter_bits)


@block
def roedf_table(lines: Lines, spec: SchedulerSpec) -> Instances:
    """Absolute deadlines registered one per cycle through a shared adder; drives `pause`."""
    n, bits = spec.n, spec.counter_bits
    deadline = tuple(spec.deadline)
    clk, rst, keys, pause = lines.clk, lines.rst, lines.keys, lines.pause
    request, complete, hold = lines.request, lines.complete, lines.hold
    absolute = [Signal(modbv(0)[bits:]) for _ in range(n)]
    registered = Signal(intbv(0)[n:])
    waiting = Signal(intbv(0)[n:])
    timer = Signal(modbv(0)[bits:])
    chosen = Signal(intbv(0)[index_bits(n) :])
    chosen_key = Signal(intbv(0)[1:])
    relative = Signal(intbv(0)[bits:])
    due = Signal(modbv(0)[bits:])

    @always_comb
    def unregistered() -> None:
        waiting.next = request & ~registered

    encoder = priority_tree(waiting, [], chosen, pause, chosen_key, n, 0)

    @always_comb
    def deadline_rom() -> None:
        relative.next = deadline[chosen]

    @always_comb
    def shared_adder() -> None:
        due.next = timer + relative

    @always(clk.posedge)
    def register() -> None:
        flags = intbv(0)[n:]
        if rst:
            timer.next = 0
            registered.next = 0
            for i in range(n):
                absolute[i].next = 0
        else:
            timer.next = timer + 1
            flags[:] = registered
            if pause:
                absolute[chosen].next = due
                flags[chosen] = 1
            registered.next = flags & ~complete

    prioritize = holder_keys(absolute, hold, keys)
    return unregistered, encoder, deadline_rom, shared_adder, prioritize, register


@policy(Algorithm.ROEDF)
def roedf_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """The statechart parts of ROEDF."""
    return PolicyHardware(
        preemptive=False,
        tracks_arrivals=False,
        key_bits=spec.counter_bits + 1,
        modular=True,
        pauses=True,
        table=roedf_table,
    )
