"""An accelerator's message pins: the message signature of each port, with netlist declarations.

The names and members come from the one contract, `rfc.lib.converters.ports`
(`accelerator_signature`): an input port ``q`` of geometry_msgs/Quaternion gives ``q_x`` …
``q_w``, ``q_valid``, ``q_ready``. Each pin also keeps its converter-side name, by which the top
level joins it to a converter. docs/accelerators.md shows examples.
"""

from __future__ import annotations

from dataclasses import dataclass

from rfc.ir.model import Port as ModelPort
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import (
    Direction,
    Port,
    PortRole,
    Side,
    accelerator_signature,
    ports_of,
)
from rfc.lib.converters.steps import ROOT
from rfc.lower.netlist import PortDecl
from rfc.messages.limits import Limits

#: The converter-side name of the message handshake.
MESSAGE = ROOT
#: The manager's cell label in the top level.
MANAGER = "manager"


@dataclass(frozen=True)
class Pin:
    """One signal of an interface between a converter and an accelerator.

    Attributes:
        role_name: Its name on a converter's accelerator side (``x``, ``msg_valid``).
        port: The port as the entity that has it declares it.
        role: What it carries.
        group: Its handshake group on the converter (``msg``, a sub-stream, an element channel).
        signal: The accelerator-side port of the signature (name, width, member).
    """

    role_name: str
    port: PortDecl
    role: PortRole
    group: str
    signal: Port


def declaration(port: Port, name: str | None = None, mirrored: bool = False) -> PortDecl:
    """The netlist declaration of a converter-convention port."""
    into = port.direction is Direction.IN
    mode = Direction.IN if into != mirrored else Direction.OUT
    return PortDecl(name or port.name, mode, port.bits, port.is_wire)


def accelerator_pins(port: ModelPort, width: int, limits: Limits) -> tuple[Pin, ...]:
    """The pins of one accelerator port, in declaration order.

    Args:
        port: The accelerator's port with its selected layout.
        width: Bus width in bits (it sets the widths of sub-stream beats).
        limits: Maxima of strings and sequences (they set length port widths).
    """
    assert port.layout is not None
    side = Side.SUBSCRIBER if port.direction is Direction.IN else Side.PUBLISHER
    chosen = plan(port.layout, width, limits)
    signature = accelerator_signature(chosen, side, port.name)
    names = {p.member: p.name for p in ports_of(chosen, side)}
    return tuple(Pin(names[s.member], declaration(s), s.role, s.group, s) for s in signature)
