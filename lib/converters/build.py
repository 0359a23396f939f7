"""Generate converters: a plan elaborated as MyHDL, converted to VHDL and Verilog.

`subscriber_top` and `publisher_top` give MyHDL top-level blocks (for MyHDL simulation or for
embedding); `generate` writes the HDL files of one converter.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from myhdl import ToVerilogWarning, ToVHDLWarning

from rfc.lib.converters.ports import Port, Side, dma_ports, ports_of
from rfc.lib.converters.publisher import publisher_ports, rfc_publisher
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.subscriber import rfc_subscriber, subscriber_ports
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.lib.types import Instances
from rfc.toolchain import convert_myhdl, elaboration


@dataclass(frozen=True)
class Converter:
    """A generated converter.

    Attributes:
        name: Entity (and module) name.
        side: Subscriber or publisher.
        plan: What it implements.
        ports: Its ports, DMA side first, in declaration order.
        files: VHDL files in compile order, then the Verilog file.
    """

    name: str
    side: Side
    plan: Plan
    ports: tuple[Port, ...]
    files: tuple[Path, ...]

    @property
    def vhdl(self) -> list[Path]:
        """The VHDL files, in compile order."""
        return [f for f in self.files if f.suffix == ".vhd"]


def entity_name(plan: Plan, side: Side) -> str:
    """A default entity name: the message's short name in snake case, then the side."""
    short = plan.layout.type_name.rsplit("/", 1)[-1]
    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", short).lower()
    return f"{snake}_{side.value}"


def subscriber_top(plan: Plan, name: str | None = None) -> Callable[..., Instances]:
    """The subscriber as a MyHDL top-level block; call it with `port_signals` of its ports."""
    name = name or entity_name(plan, Side.SUBSCRIBER)
    return top_block(name, subscriber_ports(plan), rfc_subscriber, plan=plan)


def publisher_top(plan: Plan, name: str | None = None) -> Callable[..., Instances]:
    """The publisher as a MyHDL top-level block; call it with `port_signals` of its ports."""
    name = name or entity_name(plan, Side.PUBLISHER)
    return top_block(name, publisher_ports(plan), rfc_publisher, plan=plan)


def generate(plan: Plan, side: Side, directory: Path, name: str | None = None) -> Converter:
    """Write the VHDL (and Verilog) of one converter into `directory`.

    Args:
        plan: From `rfc.lib.converters.plan.plan`.
        side: Which converter.
        directory: Output folder, created when missing.
        name: Entity name; `entity_name` when omitted.

    Returns:
        The converter and its files.
    """
    name = name or entity_name(plan, side)
    ports = (*dma_ports(plan, side), *ports_of(plan, side))
    top = subscriber_top if side is Side.SUBSCRIBER else publisher_top
    header = f"{name}: {side.value} of {plan.layout.display_name}, {8 * plan.width}-bit bus (rfc)"
    with elaboration(), warnings.catch_warnings():
        # MyHDL notes every unread or constant internal signal; the designs have many by plan.
        warnings.simplefilter("ignore", ToVHDLWarning)
        warnings.simplefilter("ignore", ToVerilogWarning)
        instance = top(plan, name)(**port_signals(ports))
        files = convert_myhdl(instance, name, directory, header=header)
    return Converter(name, side, plan, ports, tuple(files))
