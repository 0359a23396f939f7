"""The ports of the simulated logic that rfc's cocotb harnesses drive, named for the type checker.

cocotb hands a test the top level as a handle whose ports are looked up by name at run time;
these protocols name the ports the harnesses use with their handle types, so the harnesses are
checked like the rest of rfc. Every top of the system contract (docs/runtime.md) has them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

if TYPE_CHECKING:
    from cocotb.handle import LogicArrayObject, LogicObject


class StreamTop(Protocol):
    """A top with the clock, the active-low reset and the two DMA streams (by their prefixes)."""

    aclk: LogicObject
    aresetn: LogicObject
    s_axis_mm2s_tkeep: LogicArrayObject


@runtime_checkable
class BusyTop(Protocol):
    """A top that says, one bit per block it watches, which blocks still work (``busy``)."""

    busy: LogicArrayObject
