"""NPFP and PFP: fixed priorities, lower index wins; no priority table to compute.

Set Grant is the key-less priority tree (a priority encoder) over the requesters. PFP runs it
on every cycle; NPFP only when idle or at the holder's `tlast`.
"""

from __future__ import annotations

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
