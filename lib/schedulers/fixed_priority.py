"""NPFP and PFP: fixed priorities, lower index wins; no priority table to compute.

Set Grant is the key-less priority tree (a priority encoder) over the requesters. PFP runs it
on every cycle; NPFP only when idle or at the holder's `tlast`.
"""

from __future__ import annotations

from rfc.lib.schedulers.registry import policy
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.lib.schedulers.statechart import PolicyHardware


def fixed_priority_hardware(preemptive: bool) -> PolicyHardware:
    """The statechart parts of PFP (`preemptive`) or NPFP."""
    return PolicyHardware(
        preemptive=preemptive,
        tracks_arrivals=False,
        key_bits=0,
        modular=False,
        pauses=False,
        table=None,
    )


@policy(Algorithm.NPFP)
def npfp_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """NPFP: the holder keeps its grant until its ``tlast``."""
    return fixed_priority_hardware(preemptive=False)


@policy(Algorithm.PFP)
def pfp_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """PFP: a lower index takes the grant on any cycle."""
    return fixed_priority_hardware(preemptive=True)
