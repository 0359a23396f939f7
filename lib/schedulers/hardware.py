"""Build the hardware of any scheduler spec, and wrap it as a top-level entity.

`scheduler_hardware` is the block of a `SchedulerSpec` (the statechart with its algorithm's
parts) or a `CompositionSpec`, on the ports (clk, rst, request, last, ready, offer, grant,
spec). `scheduler_top` is the entity rfc generates: clk, rst, request, last, ready in; grant
out (docs/schedulers.md, "Interface").
"""

from __future__ import annotations

from myhdl import ResetSignal, Signal, block, intbv

# Each algorithm's module registers its hardware on import.
from rfc.lib.schedulers import edf, fixed_priority, lru, lst  # noqa: F401
from rfc.lib.schedulers.composition import composition
from rfc.lib.schedulers.ports import SchedulerBlock, SchedulerPorts
from rfc.lib.schedulers.registry import policy_hardware
from rfc.lib.schedulers.spec import AnySchedulerSpec, CompositionSpec
from rfc.lib.schedulers.statechart import statechart
from rfc.lib.types import Instances, SignalLike
from rfc.toolchain import start_new_design


@block
def scheduler_hardware(
    clk: SignalLike,
    rst: SignalLike,
    request: SignalLike,
    last: SignalLike,
    ready: SignalLike,
    offer: SignalLike,
    grant: SignalLike,
    spec: AnySchedulerSpec,
) -> Instances:
    """The hardware of `spec`: a composition of schedulers, or one algorithm's statechart."""
    ports = SchedulerPorts(clk, rst, request, last, ready, offer, grant)
    if isinstance(spec, CompositionSpec):
        return composition(ports, spec, scheduler_hardware)
    return statechart(ports, spec, policy_hardware(spec))


def scheduler_top(spec: AnySchedulerSpec) -> SchedulerBlock:
    """The block function of the generated entity.

    Its ports are (clk, rst, request, last, ready, grant) only: the spec is baked in and the
    offer kept inside (MyHDL takes only signals as ports of the top).
    """

    @block
    def scheduler(
        clk: SignalLike,
        rst: SignalLike,
        request: SignalLike,
        last: SignalLike,
        ready: SignalLike,
        grant: SignalLike,
    ) -> Instances:
        offer = Signal(intbv(0)[spec.n :])
        return scheduler_hardware(clk, rst, request, last, ready, offer, grant, spec)

    return scheduler


def top_instance(spec: AnySchedulerSpec) -> Instances:
    """An elaborated `scheduler_top` with fresh port signals (for conversion or simulation)."""
    start_new_design()
    return scheduler_top(spec)(*top_ports(spec))


def top_ports(spec: AnySchedulerSpec) -> tuple[SignalLike, ...]:
    """Fresh (clk, rst, request, last, ready, grant) signals of the right widths."""
    return (
        Signal(bool(0)),
        ResetSignal(1, active=1, isasync=False),
        Signal(intbv(0)[spec.n :]),
        Signal(intbv(0)[spec.n :]),
        Signal(bool(1)),
        Signal(intbv(0)[spec.n :]),
    )
