"""LRU: a priority list kept as one rank per input; the input granted moves to the bottom.

Rank 0 is the top of the list. Set Grant picks the requester of smallest rank (only requesters
are considered) when idle or at `tlast`. On the edge it grants input j of rank r, j's rank
becomes N-1 and every rank above r moves up by one, so the ranks stay a permutation — no per-
input arithmetic beyond a comparison and a decrement, and no N x N age matrix.
"""

from __future__ import annotations

from myhdl import always, block

from rfc.lib.schedulers.priority_tree import index_bits
from rfc.lib.schedulers.registry import policy
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.lib.schedulers.statechart import Lines, PolicyHardware
from rfc.lib.types import Instances


@block
def lru_table(lines: Lines, spec: SchedulerSpec) -> Instances:
    """The ranks (they are the tree's keys); reset to the input indices."""
    n = spec.n
    bottom = n - 1
    clk, rst, keys = lines.clk, lines.rst, lines.keys
    selected, best_valid, best_key = lines.selected, lines.best_valid, lines.best_key

    @always(clk.posedge)
    def rerank() -> None:
        if rst:
            for i in range(n):
                keys[i].next = i
        elif selected and best_valid:
            for i in range(n):
                if keys[i] == best_key:
                    keys[i].next = bottom
                elif keys[i] > best_key:
                    keys[i].next = keys[i] - 1

    return rerank


@policy(Algorithm.LRU)
def lru_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """The statechart parts of LRU."""
    return PolicyHardware(
        preemptive=False,
        tracks_arrivals=False,
        key_bits=index_bits(spec.n),
        modular=False,
        pauses=False,
        table=lru_table,
    )
