"""LST: least slack time first, preemptive; slack s = d - t - c per pending message.

A slack counter per input loads D_i - T_i - 1 (biased) on arrival — its slack one cycle later —
and then loses one per cycle while its message waits; on a cycle its beat moves it keeps its
slack (d - t and c both shrink by one). Set Grant compares the next slack values on every cycle.
Ties: the holder keeps the grant; among the others the lowest index wins. Two messages whose
slacks cross therefore swap the grant at most once per two cycles (the paper's laxity ties).
"""

from __future__ import annotations

from myhdl import block

from rfc.lib.schedulers.countdown import countdown_hardware, countdown_table
from rfc.lib.schedulers.registry import policy
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.lib.schedulers.statechart import Lines, PolicyHardware
from rfc.lib.types import Instances


@block
def lst_table(lines: Lines, spec: SchedulerSpec) -> Instances:
    """Slack counters: load D_i - T_i - 1 (biased) on arrival, count down while waiting."""
    bias = 1 << (spec.counter_bits - 1)
    loads = [d - t - 1 + bias for t, d in zip(spec.transfer, spec.deadline, strict=True)]
    return countdown_table(lines, loads, spec.counter_bits, True)


@policy(Algorithm.LST)
def lst_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """The statechart parts of LST."""
    return countdown_hardware(lst_table, spec.counter_bits)
