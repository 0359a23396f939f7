"""The Vivado block design of a system, derived from the same netlist as its VHDL top level.

In IP Integrator the generated entities become module-reference cells and every signal of the
netlist becomes one `connect_bd_net`; the netlist's own ports become the infrastructure around
them: `aclk` the processing system's FCLK_CLK0, `rst` (the inverse of `aresetn`) the reset
block's `peripheral_reset`, and the two AXI-Stream port groups the DMA's MM2S and S2MM
interfaces. Constants become xlconstant cells. So the block design and the simulated top level
cannot disagree: they are two renderings of one wiring.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

from rfc.lib.converters.ports import Direction
from rfc.lower.netlist import Net, Netlist, NetlistError

#: The netlist's ports that the infrastructure drives or reads.
CLOCK = "aclk"
RESET_N = "aresetn"
RESET = "rst"
MM2S = "s_axis_mm2s"
S2MM = "m_axis_s2mm"


@dataclass(frozen=True)
class BlockDesign:
    """The generated part of the block design.

    Attributes:
        cells: ``(cell, module)`` for every generated entity instance, ``(cell, module, vlnv)``
            for a vendor IP core.
        nets: ``(net, pins)``, pins as ``cell/pin``; exactly one of them drives the net.
        constants: ``(cell, width, value)`` of the xlconstant cells; each drives ``cell/dout``.
        clock_pins: Pins on the system clock.
        reset_pins: Pins on the active-high reset.
        dma_mm2s: The interface (``cell/prefix``) the DMA's MM2S stream feeds.
        dma_s2mm: The interface that feeds the DMA's S2MM stream.
    """

    cells: tuple[tuple[str, ...], ...]
    nets: tuple[tuple[str, tuple[str, ...]], ...]
    constants: tuple[tuple[str, int, int], ...]
    clock_pins: tuple[str, ...]
    reset_pins: tuple[str, ...]
    dma_mm2s: str
    dma_s2mm: str


def block_design(netlist: Netlist) -> BlockDesign:
    """Derive the block design from a system netlist (see the module docstring).

    Raises:
        NetlistError: The netlist slices a signal or connects the DMA streams to more than one
            interface: it cannot be drawn in IP Integrator.
    """
    netlist.check()
    cells: list[tuple[str, ...]] = []
    pins: dict[str, list[str]] = defaultdict(list)
    constants: list[tuple[str, int, int]] = []
    streams: dict[str, set[str]] = {MM2S: set(), S2MM: set()}
    for label, entity, connections in netlist.instances():
        cells.append((label, entity.name, entity.vlnv) if entity.vlnv else (label, entity.name))
        for port, net in connections.items():
            if net is None:
                continue
            pin = f"{label}/{port}"
            if net.signal is None:
                name = f"const_{len(constants)}"
                constants.append((name, net.bits, int(net.text.strip("\"'"), 2)))
                pins[f"{name}_net"] += [f"{name}/dout", pin]
                continue
            _whole(net, pin)
            stream = next((s for s in streams if net.signal.startswith(f"{s}_")), None)
            if stream is not None:
                streams[stream].add(f"{label}/{port.removesuffix(net.signal[len(stream) :])}")
                continue
            pins[net.signal].append(pin)
    outputs = {p.name for p in netlist.entity.ports if p.mode is Direction.OUT}
    for target, source in netlist.assignments():
        if target.signal in outputs and source.signal in pins:
            # a copy of a net onto a top-level output (the status ports, docs/protocol.md):
            # the processor reads the counters through the manager's status chunk instead
            continue
        if target.signal != RESET or source.text != f"not {RESET_N}":
            raise NetlistError(f"{target.text} <= {source.text} has no block-design form")
    return BlockDesign(
        cells=tuple(cells),
        # a net of one pin is an output nothing in the design reads: IP Integrator cannot
        # draw it, so it stays open
        nets=tuple(
            (name, tuple(members))
            for name, members in pins.items()
            if name not in (CLOCK, RESET) and len(members) > 1
        ),
        constants=tuple(constants),
        clock_pins=tuple(pins.get(CLOCK, ())),
        reset_pins=tuple(pins.get(RESET, ())),
        dma_mm2s=_single(streams[MM2S], MM2S),
        dma_s2mm=_single(streams[S2MM], S2MM),
    )


def _whole(net: Net, pin: str) -> None:
    if "(" in net.text:
        raise NetlistError(f"{pin} takes part of {net.signal}: a block design needs whole nets")


def _single(interfaces: set[str], stream: str) -> str:
    if len(interfaces) != 1:
        raise NetlistError(f"the {stream} stream must reach exactly one interface: {interfaces}")
    return next(iter(interfaces))


def tcl_word(value: object) -> str:
    """One Tcl word: braced when it holds anything but plain characters."""
    text = str(value)
    if text and all(c.isalnum() or c in "_-./:" for c in text):
        return text
    return "{" + text + "}"


def tcl_list(values: object) -> str:
    """A Tcl list of words (nested tuples and lists become nested lists)."""
    if isinstance(values, tuple | list):
        return (
            "{"
            + " ".join(tcl_list(v) if isinstance(v, tuple | list) else tcl_word(v) for v in values)
            + "}"
        )
    return tcl_word(values)
