"""The top level's ``busy`` port: one bit per block that may still owe the processor a message.

Every hardware accelerator block gets a watch (`rfc.lib.busy`) on its message handshakes, and
every publisher one that is high while a message is offered to it or its frame is on its DMA
side (a frame may wait there for the scheduler's grant without a beat moving); bit i of
``busy`` is the watch of the i-th name of `watched_blocks`.
Simulated replays read it so that they never call the logic idle while an accelerator
computes without DMA traffic (docs/runtime.md). Nothing in the block design reads it, so
synthesis removes the watches.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from rfc.ir.model import BlockKind, Design
from rfc.lib.busy import busy_body
from rfc.lib.converters.ports import Direction, Port, PortRole
from rfc.lower.netlist import Net, PortDecl, constant
from rfc.lower.system.components import Component, convert
from rfc.lower.system.interfaces import MESSAGE
from rfc.lower.system.top import Interface, Terminal, TopBuilder
from rfc.passes.names import snake_identifier as identifier

#: The top-level port.
BUSY = "busy"
#: An input's handshake as nets: valid, ready.
_Input = tuple[Net, Net]
#: An output's handshake as nets: valid, ready, last.
_Output = tuple[Net, Net, Net]


def watched_blocks(design: Design) -> tuple[str, ...]:
    """The blocks the ``busy`` bits watch, bit 0 first: hardware accelerators, then publishers."""
    infrastructure = design.infrastructure
    assert infrastructure is not None
    accelerators = [
        block.name
        for block in design.blocks_of(BlockKind.ACCELERATOR)
        if block.name not in infrastructure.software
        and {port.direction for port in block.ports} == set(Direction)
    ]
    return (*accelerators, *(converter.block for converter in infrastructure.publishers))


def busy_port(design: Design) -> tuple[PortDecl, ...]:
    """The top level's ``busy`` port, or none when nothing is watched."""
    count = len(watched_blocks(design))
    return (PortDecl(BUSY, Direction.OUT, count),) if count else ()


def watch_blocks(
    builder: TopBuilder,
    design: Design,
    interfaces: Mapping[tuple[str, str], Interface],
    directory: Path,
) -> list[Component]:
    """Add a watch per watched block (after all wiring) and drive ``busy``; its components."""
    names = watched_blocks(design)
    if not names:
        return []
    prefix = identifier(design.project.name)
    components: dict[tuple[int, int], Component] = {}
    top = builder.netlist.port(BUSY)
    assert design.infrastructure is not None
    publishers = {c.block: identifier(c.block) for c in design.infrastructure.publishers}
    for bit, name in enumerate(names):
        if name in publishers:
            inputs, outputs = _publisher(builder, interfaces[(name, "in0")], publishers[name])
        else:
            inputs, outputs = _accelerator(builder, design, interfaces, name)
        shape = (len(inputs), len(outputs))
        if shape not in components:
            entity = f"{prefix}_busy{shape[0]}x{shape[1]}"
            components[shape] = _component(*shape, directory, entity)
        label = f"{identifier(name)}_busy_watch"
        builder.cell(label, components[shape].entity)
        for side, handshakes in (("in", inputs), ("out", outputs)):
            for index, nets in enumerate(handshakes):
                for signal, net in zip(("valid", "ready", "last"), nets, strict=False):
                    builder.connect(Terminal(label, f"{side}{index}_{signal}"), net)
        builder.netlist.assign(top.bit(bit), builder.output(Terminal(label, BUSY)))
    return list(components.values())


def _accelerator(
    builder: TopBuilder,
    design: Design,
    interfaces: Mapping[tuple[str, str], Interface],
    name: str,
) -> tuple[list[_Input], list[_Output]]:
    block = design.block(name)
    inputs: list[_Input] = []
    outputs: list[_Output] = []
    for port in block.ports:
        pins = interfaces[(name, port.name)]
        valid, ready = (_net(builder, pins[f"{MESSAGE}_{s}"]) for s in ("valid", "ready"))
        if port.direction is Direction.IN:
            inputs.append((valid, ready))
        else:
            outputs.append((valid, ready, constant(1, 1, wire=True)))
    return inputs, outputs


def _publisher(
    builder: TopBuilder, interface: Interface, label: str
) -> tuple[list[_Input], list[_Output]]:
    """Busy while a message is offered to it or a frame of it waits or moves on its DMA side.

    Neither counts as taken (ready 0) and the one output always ends: the watch owes nothing.
    """
    never, always = constant(0, 1, wire=True), constant(1, 1, wire=True)
    offered = _net(builder, interface[f"{MESSAGE}_valid"])
    framing = _net(builder, Terminal(label, "m_axis_tvalid"))
    return [(offered, never), (framing, never)], [(always, always, always)]


def _net(builder: TopBuilder, terminal: Terminal) -> Net:
    """The net on a cell's port; an input nothing drives reads as 0."""
    return builder.net(terminal) or constant(0, 1, wire=True)


def _component(inputs: int, outputs: int, directory: Path, name: str) -> Component:
    wire = PortRole.VALID
    handshake = ("valid", "ready", "last")
    ports = [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
    ]
    for index in range(inputs):
        ports += [Port(f"in{index}_{s}", 1, Direction.IN, wire) for s in ("valid", "ready")]
    for index in range(outputs):
        ports += [Port(f"out{index}_{s}", 1, Direction.IN, wire) for s in handshake]
    ports.append(Port(BUSY, 1, Direction.OUT, wire))
    what = f"busy watch of a block with {inputs} inputs and {outputs} outputs (rfc)"
    return convert(name, ports, busy_body, directory, what, inputs=inputs, outputs=outputs)
