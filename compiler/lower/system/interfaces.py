"""How an accelerator's ports are named: rfc's accelerator convention.

An accelerator port ``p`` carrying a message has the ports a converter of that message has on
its accelerator side (`rfc.lib.converters.plan.accelerator_ports`), mirrored, each prefixed with
``p_``; the message handshake ``msg_valid``/``msg_ready`` becomes ``p_valid``/``p_ready``. An
input port is fed as a subscriber converter feeds it (it has no ``msg_error``); an output port
feeds a publisher converter. So ``q: geometry_msgs/Quaternion`` in gives ``q_x`` … ``q_w``,
``q_valid``, ``q_ready``. docs/accelerators.md shows an example.
"""

from __future__ import annotations

from dataclasses import dataclass

from rfc.ir.model import Direction as PortDirection
from rfc.ir.model import Port as ModelPort
from rfc.lib.converters.plan import accelerator_ports
from rfc.lib.converters.ports import Direction, Port, PortRole, Side
from rfc.lib.converters.toplevel import WIRES
from rfc.lower.netlist import Mode, PortDecl
from rfc.messages.limits import Limits

#: The converter-side name of the message handshake.
MESSAGE = "msg"


@dataclass(frozen=True)
class Pin:
    """One signal of an interface between a converter and an accelerator.

    Attributes:
        role_name: Its name on a converter's accelerator side (``x``, ``msg_valid``).
        port: The port as the entity that has it declares it.
        role: What it carries.
        group: Its handshake group on the converter (``msg``, a sub-stream, an element channel).
    """

    role_name: str
    port: PortDecl
    role: PortRole
    group: str


def is_wire(port: Port) -> bool:
    """Whether a converter-convention port is a ``std_logic`` (else a vector)."""
    return port.role in WIRES or port.role is PortRole.RESET or port.ros_type == "bool"


def declaration(port: Port, name: str | None = None, mirrored: bool = False) -> PortDecl:
    """The netlist declaration of a converter-convention port."""
    into = port.direction is Direction.IN
    mode = Mode.IN if into != mirrored else Mode.OUT
    return PortDecl(name or port.name, mode, port.bits, is_wire(port))


def accelerator_pin_name(port_name: str, role_name: str) -> str:
    """The accelerator's port for a converter-side name (``q`` + ``msg_valid`` → ``q_valid``)."""
    if role_name.startswith(f"{MESSAGE}_"):
        return f"{port_name}_{role_name.removeprefix(f'{MESSAGE}_')}"
    return f"{port_name}_{role_name}"


def accelerator_pins(port: ModelPort, width: int, limits: Limits) -> tuple[Pin, ...]:
    """The pins of one accelerator port, in declaration order.

    Args:
        port: The accelerator's port with its selected layout.
        width: Bus width in bits (it sets the widths of sub-stream beats).
        limits: Maxima of strings and sequences (they set length port widths).
    """
    assert port.layout is not None
    side = Side.SUBSCRIBER if port.direction is PortDirection.IN else Side.PUBLISHER
    pins = []
    for converter_port in accelerator_ports(port.layout, width, side, limits):
        if converter_port.role is PortRole.ERROR and converter_port.group == MESSAGE:
            continue  # the subscriber drops malformed frames; the accelerator never sees them
        name = accelerator_pin_name(port.name, converter_port.name)
        decl = declaration(converter_port, name, mirrored=True)
        pins.append(Pin(converter_port.name, decl, converter_port.role, converter_port.group))
    return tuple(pins)
