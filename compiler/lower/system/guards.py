"""What stands between a subscriber and its consumers so that malformed frames end in the logic.

A subscriber whose consumers get only fixed-size fields presents a whole frame at once, as
registers with ``msg_valid``: a *drop gate* behind it takes a rejected record before any
consumer sees it. A subscriber that hands strings or sequences on as sub-streams gets a *frame
guard* in front instead: the frame is checked whole in a buffer before the subscriber sees it
(`rfc.lib.converters.guard`), or only its bytes before a last primitive sequence, against the
size its chunk header declared, which the guard reads off the DMA stream into the manager
(`rfc.lib.converters.prefix_guard`). Either counts what it drops by reason; the counts go to the
manager, which sends them to the processor in a status chunk, and to the top level's status
ports (docs/protocol.md).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from rfc.ir.infrastructure import Converter
from rfc.lib.converters.buffers import Buffer
from rfc.lib.converters.chunk_length import dma_tap, dma_tap_ports, length_port
from rfc.lib.converters.malformed import DROP_REASONS, counter_name, status_port
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side
from rfc.lib.converters.prefix_guard import DECLARED, prefix_guard, prefix_guard_ports
from rfc.lib.converters.prefix_plan import checking_plan
from rfc.lib.converters.steps import Plan
from rfc.lower.system.components import Component, convert, gate_component, guard_component
from rfc.lower.system.interfaces import MANAGER, MESSAGE
from rfc.lower.system.top import Interface, Terminal, TopBuilder
from rfc.messages.limits import Limits
from rfc.passes.check_hardware import subscriber_guard

#: Joins a converter's DMA side to the manager: (builder, cell label, converter, side).
DmaWiring = Callable[[TopBuilder, str, Converter, Side], None]
#: The top level's DMA stream into the manager, which prefix guards read chunk headers from.
MM2S = "s_axis_mm2s"
STREAM = ("tdata", "tkeep", "tvalid", "tready", "tlast")


class SubscriberGuards:
    """The gates and guards of a system's subscribers, and the components they need.

    Args:
        prefix: The project's identifier, which the shared gate entity's name starts with.
        width: Bus width in bits.
        directory: Where the VHDL goes.
        limits: The maxima the converters are built for (they size the guards' buffers).
    """

    def __init__(self, prefix: str, width: int, directory: Path, limits: Limits) -> None:
        self.prefix, self.width, self.directory, self.limits = prefix, width, directory, limits
        self.components: list[Component] = []
        self.buffers: dict[str, tuple[Buffer, ...]] = {}
        self._gate: Component | None = None
        self._tapped: dict[int, str] = {}  # prefix guards by subscriber id

    def protect(
        self,
        builder: TopBuilder,
        label: str,
        converter: Converter,
        interface: Interface,
        wire_dma: DmaWiring,
    ) -> Interface:
        """Wire subscriber `label` to the manager through its protection.

        Returns:
            What its consumers see of it.
        """
        chosen = plan(converter.layout, self.width, self.limits)
        guard = subscriber_guard(converter, chosen, self.limits)
        if guard is None:
            wire_dma(builder, label, converter, Side.SUBSCRIBER)
            return self._gated(builder, label, interface, converter.id)
        self._guard(builder, label, converter, chosen, guard, wire_dma)
        return interface

    def dma_input(self, builder: TopBuilder, manager: Terminal) -> None:
        """Join the top level's DMA stream to the manager's input `manager` (its group).

        With prefix guards the stream passes a tap that reads each chunk's declared length for
        them (`rfc.lib.converters.chunk_length.dma_tap`); the tap adds no register.
        """
        if not self._tapped:
            for signal in STREAM:
                builder.connect(
                    Terminal(manager.cell, f"{manager.port}_{signal}"),
                    builder.netlist.port(f"{MM2S}_{signal}"),
                )
            return
        cell, ids = "chunk_tap", sorted(self._tapped)
        ports = dma_tap_ports(self.width // 8, ids)
        tap = convert(f"{self.prefix}_dma_tap", ports, dma_tap, self.directory,
                      "chunk lengths for the prefix guards (rfc)", subscribers=ids)  # fmt: skip
        self.components.append(tap)
        builder.cell(cell, tap.entity)
        for signal in STREAM:
            dma = builder.netlist.port(f"{MM2S}_{signal}")
            builder.connect(Terminal(cell, f"s_axis_{signal}"), dma)
            tap_out = Terminal(cell, f"m_axis_{signal}")
            manager_in = Terminal(manager.cell, f"{manager.port}_{signal}")
            if signal == "tready":
                builder.wire(manager_in, tap_out)  # the manager's ready, back through the tap
            else:
                builder.wire(tap_out, manager_in)
        for ident in ids:
            builder.wire(
                Terminal(cell, length_port(ident)), Terminal(self._tapped[ident], DECLARED)
            )

    def _gated(
        self, builder: TopBuilder, label: str, interface: Interface, subscriber: int
    ) -> Interface:
        if self._gate is None:
            self._gate = gate_component(self.directory, f"{self.prefix}_drop_gate")
            self.components.append(self._gate)
        cell = f"{label}_drop_gate"
        builder.cell(cell, self._gate.entity)
        builder.wire(interface[f"{MESSAGE}_valid"], Terminal(cell, "s_valid"))
        builder.wire(interface[f"{MESSAGE}_error"], Terminal(cell, "s_error"))
        builder.wire(Terminal(label, "error_reason"), Terminal(cell, "s_reason"))
        builder.wire(Terminal(cell, "s_ready"), interface[f"{MESSAGE}_ready"])
        _status(builder, cell, subscriber)
        valid, ready = Terminal(cell, "m_valid"), Terminal(cell, "m_ready")
        return {**interface, f"{MESSAGE}_valid": valid, f"{MESSAGE}_ready": ready}

    def _guard(
        self,
        builder: TopBuilder,
        label: str,
        converter: Converter,
        converters: Plan,
        guard: Buffer,
        wire_dma: DmaWiring,
    ) -> None:
        cell = f"{label}_guard"
        checking = checking_plan(converters)
        if checking is None:
            component = guard_component(converters, guard.words, self.directory, cell)
        else:
            what = f"prefix check of {checking.layout.display_name} frames (rfc)"
            ports = prefix_guard_ports(checking.width)
            component = convert(cell, ports, prefix_guard, self.directory, what,
                                checking=checking, depth=guard.words)  # fmt: skip
            self._tapped[converter.id] = cell
        self.components.append(component)
        self.buffers[converter.block] = (guard,)
        builder.cell(cell, component.entity)
        wire_dma(builder, cell, converter, Side.SUBSCRIBER)
        for signal in ("tdata", "tkeep", "tvalid", "tlast"):
            builder.wire(Terminal(cell, f"m_axis_{signal}"), Terminal(label, f"s_axis_{signal}"))
        builder.wire(Terminal(label, "s_axis_tready"), Terminal(cell, "m_axis_tready"))
        _status(builder, cell, converter.id)


def _status(builder: TopBuilder, cell: str, subscriber: int) -> None:
    """Give a gate's or guard's counters to the manager and to the top level's status ports."""
    for reason in DROP_REASONS:
        name = status_port(subscriber, reason)
        count = builder.output(Terminal(cell, counter_name(reason)))
        builder.connect(Terminal(MANAGER, name), count)
        builder.netlist.assign(builder.netlist.port(name), count)
