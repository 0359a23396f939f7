"""The top level of the logic: every cell of the system wired as the holistic model says.

`TopBuilder` collects cells and point-to-point wires by cell and port name, naming each net
after its driver (``<cell>_<port>``), then emits one checked `Netlist`. `wire_connection`
joins two message interfaces pin by pin through their converter-side names, so a subscriber's
``x`` meets accelerator ``q``'s ``q_x`` and its ``msg_ready`` meets ``q_ready``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from rfc.errors import RfcError
from rfc.lib.converters.ports import Direction
from rfc.lower.netlist import EntityDecl, Net, Netlist, NetlistError, PortDecl

#: The top level's clock, active-low reset and derived active-high reset.
CLOCK, RESET_N, RESET = "aclk", "aresetn", "rst"
#: The cell ports put on the clock and on the reset.
CLOCK_PORTS = frozenset({"clk", "ap_clk"})
RESET_PORTS = frozenset({"rst", "ap_rst"})


# Two names and a __str__, like rfc.cluster.Failure in shape only: a cell's port, not a job.
@dataclass(frozen=True)
class Terminal:
    """A port of a cell: ``(cell label, port name)``."""

    cell: str
    port: str

    def __str__(self) -> str:
        return f"{self.cell}.{self.port}"


#: A message interface: converter-side name → the terminal that carries it.
Interface = Mapping[str, Terminal]


class TopBuilder:
    """Cells and wires, turned into one netlist at the end.

    Args:
        entity: The top level's own name and ports.
        comment: The netlist file's header comment.
    """

    def __init__(self, entity: EntityDecl, comment: str) -> None:
        self.netlist = Netlist(entity, comment)
        self._cells: dict[str, EntityDecl] = {}
        self._connections: dict[str, dict[str, Net | None]] = {}
        self._driven: dict[Terminal, Net] = {}
        self.netlist.assign(self.netlist.signal(RESET, wire=True), f"not {RESET_N}")

    def cell(self, label: str, entity: EntityDecl) -> None:
        """Add a cell; its clock and reset ports go on the system's."""
        if label.lower() in {c.lower() for c in self._cells}:
            raise NetlistError(f"two cells labelled {label}")
        self._cells[label] = entity
        self._connections[label] = {}
        for port in entity.ports:
            if port.name in CLOCK_PORTS:
                self.connect(Terminal(label, port.name), self.netlist.port(CLOCK))
            elif port.name in RESET_PORTS:
                self.connect(Terminal(label, port.name), Net(RESET, 1, True, RESET, (0, 0)))

    def port(self, terminal: Terminal) -> PortDecl:
        """The declaration of a cell's port."""
        return self._cells[terminal.cell].port(terminal.port)

    def output(self, terminal: Terminal) -> Net:
        """The net a cell's output drives (declared on first use)."""
        port = self.port(terminal)
        if port.mode is not Direction.OUT:
            raise NetlistError(f"{terminal} is an input")
        connections = self._connections[terminal.cell]
        if connections.get(terminal.port) is None:
            signal = f"{terminal.cell}_{terminal.port}"
            connections[terminal.port] = self.netlist.signal(signal, port.bits, port.wire)
        net = connections[terminal.port]
        assert net is not None
        return net

    def net(self, terminal: Terminal) -> Net | None:
        """The net on a cell's port: an output's (declared on first use), else what drives it."""
        if self.port(terminal).mode is Direction.OUT:
            return self.output(terminal)
        return self._connections[terminal.cell].get(terminal.port)

    def connect(self, terminal: Terminal, net: Net) -> None:
        """Connect a cell's port to an existing net (a top-level port, or an output's net)."""
        connections = self._connections[terminal.cell]
        if terminal.port in connections:
            raise NetlistError(f"{terminal} connected twice")
        connections[terminal.port] = net

    def wire(self, source: Terminal, destination: Terminal) -> None:
        """Drive input `destination` from output `source`."""
        self.connect(destination, self.output(source))

    def cells(self) -> list[tuple[str, EntityDecl]]:
        """The cells added so far: label and entity."""
        return list(self._cells.items())

    def driven(self, terminal: Terminal) -> bool:
        """Whether a cell's port is connected yet."""
        return terminal.port in self._connections[terminal.cell]

    def finish(self) -> Netlist:
        """Instantiate every cell; unconnected outputs stay open.

        Raises:
            NetlistError: An input is left unconnected (a bug in the lowering).
        """
        for label, entity in self._cells.items():
            connections = self._connections[label]
            for port in entity.ports:
                connections.setdefault(port.name, None)
            self.netlist.instance(
                label, entity, {p.name: connections[p.name] for p in entity.ports}
            )
        self.netlist.check()
        return self.netlist


def wire_connection(
    builder: TopBuilder, source: Interface, destination: Interface, what: str
) -> None:
    """Join two message interfaces by their converter-side names.

    Each input of `destination` is driven by the same-named output of `source`, and each output
    of `destination` (a ready) drives the same-named input of `source`.

    Raises:
        RfcError: `destination` needs a pin `source` does not have.
    """
    for name, terminal in destination.items():
        partner = source.get(name)
        if partner is None:
            raise RfcError(
                f"{what}: the destination needs '{name}', which the source does not provide",
                hint="select the field on both sides of the connection",
            )
        if builder.port(terminal).mode is Direction.IN:
            builder.wire(partner, terminal)
        else:
            builder.wire(terminal, partner)
