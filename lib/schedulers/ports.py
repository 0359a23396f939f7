"""The ports every scheduler block shares, and their bundle for the blocks inside one.

A `SchedulerBlock` takes the ports one by one, as the manager's mux instantiates it; the
statechart and the composition inside take them as one `SchedulerPorts`. MyHDL converts the
signals a block holds in local names, not an object's attributes, so a block binds
``ports.signals()`` to local names before using them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from rfc.lib.types import Instances, SignalLike

#: A block function called as ``block(clk, rst, request, last, ready, offer, grant, spec)``.
SchedulerBlock = Callable[..., Instances]


@dataclass(frozen=True)
class SchedulerPorts:
    """A scheduler block's ports; the top-level entity has all but `offer` (docs/schedulers.md).

    Attributes:
        clk: Clock.
        rst: Synchronous reset, active high.
        request: intbv[N] in, `tvalid` of each input.
        last: intbv[N] in, `tlast` of each input.
        ready: Bool in, the channel accepts a beat this cycle.
        offer: intbv[N] out, the input offered the channel (grant before `ready`).
        grant: intbv[N] out, one-hot or zero: drives the inputs' `tready`.
    """

    clk: SignalLike
    rst: SignalLike
    request: SignalLike
    last: SignalLike
    ready: SignalLike
    offer: SignalLike
    grant: SignalLike

    def signals(self) -> tuple[SignalLike, ...]:
        """clk, rst, request, last, ready, offer, grant: to bind to a block's local names."""
        return self.clk, self.rst, self.request, self.last, self.ready, self.offer, self.grant
