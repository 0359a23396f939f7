"""A scheduler whose inputs are schedulers (paper §7.2.5), with the same interface as one.

Child c offers the channel to one of its inputs; the parent sees its input c requesting while
child c offers, with the offered input's `tlast`; the parent's grant of c is child c's `ready`,
so a child counts a beat (and its `tlast`) only when it really moved. The composite's grant is
the granted child's grant, its offer the offered child's offer.
"""

from __future__ import annotations

from myhdl import ConcatSignal, Signal, always_comb, block, intbv

from rfc.lib.converters.wiring import follow
from rfc.lib.schedulers.ports import SchedulerBlock, SchedulerPorts
from rfc.lib.schedulers.spec import CompositionSpec
from rfc.lib.types import Instances, SignalLike


@block
def composition(
    ports: SchedulerPorts,
    spec: CompositionSpec,
    build: SchedulerBlock,
) -> Instances:
    """The composite of `spec`; `build` is the block of any scheduler spec, child or parent."""
    clk, rst, request, last, ready, offer, grant = ports.signals()
    count = len(spec.children)
    parent_offer = Signal(intbv(0)[count:])
    parent_grant = Signal(intbv(0)[count:])
    wants = [Signal(bool(0)) for _ in range(count)]
    ends = [Signal(bool(0)) for _ in range(count)]
    gated_offers, grants, parts = [], [], []
    for c, (child, start) in enumerate(zip(spec.children, spec.offsets, strict=True)):
        sub_request = request(start + child.n, start)
        sub_last = last(start + child.n, start)
        offered = Signal(intbv(0)[child.n :])
        granted = Signal(intbv(0)[child.n :])
        gated = Signal(intbv(0)[child.n :])
        parts.append(
            build(clk, rst, sub_request, sub_last, parent_grant(c), offered, granted, child)
        )
        parts.append(child_port(offered, sub_last, parent_offer(c), wants[c], ends[c], gated))
        gated_offers.append(gated)
        grants.append(granted)
    parent_request = ConcatSignal(*reversed(wants))
    parent_last = ConcatSignal(*reversed(ends))
    parts.append(
        build(clk, rst, parent_request, parent_last, ready, parent_offer, parent_grant, spec.parent)
    )
    parts.append(follow(ConcatSignal(*reversed(gated_offers)), offer))
    parts.append(follow(ConcatSignal(*reversed(grants)), grant))
    return parts


@block
def child_port(
    offered: SignalLike,
    last: SignalLike,
    chosen: SignalLike,
    wants: SignalLike,
    ends: SignalLike,
    gated: SignalLike,
) -> Instances:
    """What the parent sees of one child, and the child's offer once the parent chose it."""

    @always_comb
    def summarize() -> None:
        wants.next = offered != 0
        ends.next = (offered & last) != 0
        if chosen:
            gated.next = offered
        else:
            gated.next = 0

    return summarize
