"""The adaptable statechart (paper Fig. 5): the static part every scheduler shares.

States: IDLE (no holder), GRANT (a holder; it is granted on cycles it requests and the channel
is ready) and COMPUTE (the priority table is being updated; no grant — only algorithms whose
Compute Condition needs it, ROEDF, enter it). The static part owns the holder register, the
grant, `tlast` detection and arrival detection; each algorithm supplies its Compute Condition
(the priority table and the keys it exposes) and its Set Grant rule (when to pick the most
urgent candidate again) through a `PolicyHardware`. docs/schedulers.md gives the cycle
semantics; `rfc.lib.schedulers.model.statechart` is the same machine in NumPy.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from myhdl import Signal, always, always_comb, block, intbv

from rfc.lib.schedulers.ports import SchedulerPorts
from rfc.lib.schedulers.priority_tree import index_bits, priority_tree
from rfc.lib.schedulers.spec import SchedulerSpec
from rfc.lib.types import Instances, SignalLike


@dataclass(frozen=True)
class Lines:
    """The signals a policy's table reads, then the two it drives (intbv[N] unless said otherwise).

    Attributes:
        clk: Clock.
        rst: Synchronous reset, active high.
        request: The inputs' `tvalid`.
        candidates: Requesters that may be granted next (the one completing excluded).
        pending: Inputs with a message in progress (arrival-tracking policies only).
        arrival: Inputs whose message arrives this cycle (arrival-tracking policies only).
        grant: The granted input (its beat moves this cycle).
        complete: The granted input when its beat carries `tlast`.
        hold: The holder, one-hot (kept through a pause).
        best: Index of the most urgent candidate (the tree's root).
        best_valid: Bool, some candidate exists.
        best_key: The tree root's key.
        selected: Bool, the holder register takes `best` at this clock edge.
        keys: Out, one key per input (`PolicyHardware.key_bits` wide; empty when 0).
        pause: Bool out, enter or stay in COMPUTE (policies that pause only).
    """

    clk: SignalLike
    rst: SignalLike
    request: SignalLike
    candidates: SignalLike
    pending: SignalLike
    arrival: SignalLike
    grant: SignalLike
    complete: SignalLike
    hold: SignalLike
    best: SignalLike
    best_valid: SignalLike
    best_key: SignalLike
    selected: SignalLike
    keys: list[SignalLike]
    pause: SignalLike


@dataclass(frozen=True)
class PolicyHardware:
    """An algorithm's parts of the statechart.

    Attributes:
        preemptive: Set Grant runs every cycle (else only when idle, at `tlast`, after COMPUTE).
        tracks_arrivals: The static part must provide `pending` and `arrival`.
        key_bits: Width of the keys the tree compares (0: index order only).
        modular: The keys wrap around (compared on a circle).
        pauses: The policy drives `pause` (enter or stay in COMPUTE).
        table: ``table(lines, spec)`` building the Compute Condition block: it drives
            `lines.keys` (and `lines.pause` when `pauses`); None when there is no table.
    """

    preemptive: bool
    tracks_arrivals: bool
    key_bits: int
    modular: bool
    pauses: bool
    table: Callable[..., Instances] | None


@block
def statechart(ports: SchedulerPorts, spec: SchedulerSpec, policy: PolicyHardware) -> Instances:
    """One scheduler: the static states plus `policy`'s Compute Condition and Set Grant.

    Args:
        ports: The scheduler's ports.
        spec: Generation-time constants.
        policy: The algorithm's parts.
    """
    clk, rst, request, last, ready, offer, grant = ports.signals()
    n = spec.n
    owner = Signal(intbv(0)[index_bits(n) :])
    owner_valid = Signal(bool(0))
    computing = Signal(bool(0))
    hold = Signal(intbv(0)[n:])
    candidates = Signal(intbv(0)[n:])
    complete = Signal(intbv(0)[n:])
    done = Signal(bool(0))
    seen = Signal(intbv(0)[n:])
    pending = Signal(intbv(0)[n:])
    arrival = Signal(intbv(0)[n:])
    best = Signal(intbv(0)[index_bits(n) :])
    best_valid = Signal(bool(0))
    best_key = Signal(intbv(0)[max(policy.key_bits, 1) :])
    reselect = Signal(bool(0))
    selected = Signal(bool(0))
    pause = Signal(bool(0))
    keys = [Signal(intbv(0)[policy.key_bits :]) for _ in range(n)] if policy.key_bits else []
    lines = Lines(
        clk=clk,
        rst=rst,
        request=request,
        candidates=candidates,
        pending=pending,
        arrival=arrival,
        grant=grant,
        complete=complete,
        hold=hold,
        best=best,
        best_valid=best_valid,
        best_key=best_key,
        selected=selected,
        keys=keys,
        pause=pause,
    )
    preemptive = policy.preemptive

    @always_comb
    def decode_holder() -> None:
        for i in range(n):
            hold.next[i] = owner_valid and owner == i

    @always_comb
    def offer_channel() -> None:
        if computing:
            offer.next = 0
        else:
            offer.next = hold & request

    @always_comb
    def offer_always() -> None:
        offer.next = hold & request

    # Gates the offer by `ready`; `manager.entity.spread_bit` copies a bit: alike in shape only.
    @always_comb
    def grant_channel() -> None:
        if ready:
            grant.next = offer
        else:
            grant.next = 0

    @always_comb
    def detect_tlast() -> None:
        complete.next = grant & last
        done.next = (grant & last) != 0

    @always_comb
    def exclude_completing() -> None:
        candidates.next = request & ~(grant & last)

    if policy.pauses:

        @always_comb
        def decide() -> None:
            reselect.next = preemptive or computing or done or not owner_valid
            selected.next = (preemptive or computing or done or not owner_valid) and not pause

        @always(clk.posedge)
        def set_grant() -> None:
            if rst:
                owner.next = 0
                owner_valid.next = 0
                computing.next = 0
            elif pause:
                computing.next = 1
                if done:
                    owner_valid.next = 0
            elif reselect:
                computing.next = 0
                owner.next = best
                owner_valid.next = best_valid

    else:

        @always_comb
        def decide() -> None:
            selected.next = preemptive or done or not owner_valid

        @always(clk.posedge)
        def set_grant() -> None:
            if rst:
                owner.next = 0
                owner_valid.next = 0
            elif selected:
                owner.next = best
                owner_valid.next = best_valid

    parts = [
        decode_holder,
        offer_channel if policy.pauses else offer_always,
        grant_channel,
        detect_tlast,
        exclude_completing,
        decide,
        set_grant,
        priority_tree(
            candidates, keys, best, best_valid, best_key, n, policy.key_bits, policy.modular
        ),
    ]
    if policy.table is not None:
        parts.append(policy.table(lines, spec))
    if policy.tracks_arrivals:
        parts.append(arrival_detector(clk, rst, request, complete, seen, pending, arrival))
    return parts


@block
def arrival_detector(
    clk: SignalLike,
    rst: SignalLike,
    request: SignalLike,
    complete: SignalLike,
    seen: SignalLike,
    pending: SignalLike,
    arrival: SignalLike,
) -> Instances:
    """A message arrives when `tvalid` rises, or stays high after the previous `tlast`."""

    @always_comb
    def classify() -> None:
        pending.next = request | seen
        arrival.next = request & ~seen

    @always(clk.posedge)
    def remember() -> None:
        if rst:
            seen.next = 0
        else:
            seen.next = (request | seen) & ~complete

    return classify, remember
