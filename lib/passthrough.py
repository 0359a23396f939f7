"""An accelerator that forwards its input message unchanged, for any message type.

`pass_through` follows rfc's port convention (docs/accelerators.md) for one input port ``in0``
and one output port ``out0`` of the same type: every pin of ``out0`` is driven by the same pin
of ``in0`` (fields, lengths, sub-streams), and readys flow back. It takes its ports as
keywords, so one block serves every message type; name it as a MyHDL accelerator's ``top``.
"""

from __future__ import annotations

from typing import Any

from myhdl import block

from rfc.lib.converters.wiring import follow


@block
def pass_through(clk: Any, rst: Any, **ports: Any) -> Any:
    """Forward ``in0`` to ``out0``; the pins only the input side has stay unread."""
    wires = []
    for name, target in ports.items():
        if not name.startswith("out0_"):
            continue
        partner = ports["in0_" + name.removeprefix("out0_")]
        wires.append(follow(target, partner) if name.endswith("ready") else follow(partner, target))
    return wires
