"""A frame guard's checker: a second subscriber of the plan whose verdict alone counts.

Both guards (`rfc.lib.converters.guard`, `rfc.lib.converters.prefix_guard`) feed the frame
they hold to a checker while they store it; every output of the checker is taken at once (the
guard holds those inputs high), and its record's ``msg_error`` and ``error_reason`` decide
whether the frame goes on. Its fields are read by nobody, so it captures none
(`without_fields`).
"""

from __future__ import annotations

from dataclasses import replace

from myhdl import Signal, intbv

from rfc.lib.converters.ports import COUNTER_BITS, Direction, Side, ports_of
from rfc.lib.converters.steps import Plan, Record, Slot, SlotRole
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.types import SignalLike


def without_fields(plan: Plan) -> Plan:
    """`plan` with no field port: the walk, lengths and CDR header on which the verdict rests.

    A checker built from it holds none of the subscriber's field registers, which synthesis
    would remove and GHDL would run at every clock edge (Franka's guard had 65).
    """
    steps = tuple(
        replace(step, slots=tuple(_unported(slot) for slot in step.slots))
        if isinstance(step, Record)
        else step
        for step in plan.steps
    )
    return replace(plan, steps=steps)


def _unported(slot: Slot) -> Slot:
    return replace(slot, port=None) if slot.role is SlotRole.FIELD else slot


def checker_signals(plan: Plan) -> tuple[dict[str, SignalLike], list[SignalLike]]:
    """A checker's port signals by name, and those of them its consumer drives (held high)."""
    ports = ports_of(plan, Side.SUBSCRIBER)
    checker = port_signals(ports)
    return checker, [checker[p.name] for p in ports if p.direction is Direction.IN]


def checker_ports(
    clk: SignalLike,
    rst: SignalLike,
    stream: tuple[SignalLike, ...],
    cause: SignalLike,
    checker: dict[str, SignalLike],
) -> dict[str, SignalLike]:
    """Every port of a checker: the frame's `stream` in, its reason out on `cause`.

    Args:
        clk: Clock.
        rst: The checker's reset.
        stream: The frame as the checker reads it: tdata, tkeep, tvalid, tready, tlast.
        cause: The checker's ``error_reason``.
        checker: The rest of its ports (`checker_signals`).
    """
    tdata, tkeep, tvalid, tready, tlast = stream
    return {
        "clk": clk,
        "rst": rst,
        "s_axis_tdata": tdata,
        "s_axis_tkeep": tkeep,
        "s_axis_tvalid": tvalid,
        "s_axis_tready": tready,
        "s_axis_tlast": tlast,
        "error_count": Signal(intbv(0)[COUNTER_BITS:]),  # the guard counts by reason instead
        "error_reason": cause,
        **checker,
    }
