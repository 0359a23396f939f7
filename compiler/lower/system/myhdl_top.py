"""The structural top level as MyHDL instances: the whole logic in MyHDL's simulator.

Every component rfc generates is converted from a MyHDL block (`Component.myhdl`), and so is
every MyHDL accelerator; the top level itself is only a `Netlist`. `myhdl_logic` builds the same
wiring from MyHDL signals — one per netlist signal, a shadow for each bit or slice read, parts
joined for a vector driven bit by bit, a copy per assignment — so ``rfc sim --backend myhdl``
runs the logic without VHDL. A VHDL accelerator or a vendor core has no MyHDL block: such a
logic has no MyHDL form.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from myhdl import ConcatSignal, ResetSignal, Signal, always_comb, block, intbv

from rfc.lib.converters.ports import Direction
from rfc.lib.converters.wiring import follow
from rfc.lower.netlist import Net, Netlist
from rfc.lower.system.top import RESET

Block = Callable[..., Any]


def missing_blocks(netlist: Netlist, blocks: Mapping[str, Block]) -> list[str]:
    """The entities of the netlist that have no MyHDL block, in instance order."""
    names = (entity.name for _, entity, _ in netlist.instances())
    return list(dict.fromkeys(n for n in names if n not in blocks))


def myhdl_logic(netlist: Netlist, blocks: Mapping[str, Block]) -> Block:
    """A block factory of the whole logic, taking the top level's port signals by name.

    Ports it is not given (status counters, ``busy``) get signals of their own.

    Raises:
        ValueError: An entity has no MyHDL block (see `missing_blocks`).
    """
    if missing := missing_blocks(netlist, blocks):
        raise ValueError(f"no MyHDL block for {', '.join(missing)}")

    @block
    def logic(**ports: Any) -> Any:
        # MyHDL wants every instance created in the block's own frame
        return [factory(**arguments) for factory, arguments in _Wiring(netlist, ports).plan(blocks)]

    return logic


def _signal(bits: int, wire: bool, name: str = "") -> Any:
    if name == RESET:
        return ResetSignal(0, active=1, isasync=False)
    return Signal(bool(0)) if wire else Signal(intbv(0)[bits:])


@block
def _invert(target: Any, source: Any) -> Any:
    @always_comb
    def invert() -> None:
        target.next = not source

    return invert


class _Wiring:
    """The netlist's signals as MyHDL signals, and the processes that join them."""

    def __init__(self, netlist: Netlist, ports: Mapping[str, Any]) -> None:
        self.netlist = netlist
        self.processes: list[tuple[Block, dict[str, Any]]] = []
        self.signals: dict[str, Any] = {}
        for port in netlist.entity.ports:
            given = ports.get(port.name)
            self.signals[port.name] = given if given is not None else _signal(port.bits, port.wire)
        widths: dict[str, tuple[int, bool]] = {}
        for net in self._nets():
            if net.signal is None or net.signal in self.signals:
                continue
            if net.text == net.signal:
                widths[net.signal] = (net.bits, net.wire)
            else:  # a bit or slice: the vector is at least that wide
                bits, wire = widths.get(net.signal, (0, False))
                widths[net.signal] = (max(bits, net.span[0] + 1), wire)
        for name, (bits, wire) in widths.items():
            self.signals[name] = _signal(bits, wire, name)
        self.parts: dict[str, Any] = {}  # a driven bit or slice → its own signal
        self._join_parts()

    def _nets(self) -> list[Net]:
        nets = [n for _, _, c in self.netlist.instances() for n in c.values() if n is not None]
        return nets + [n for pair in self.netlist.assignments() for n in pair]

    def _driven(self) -> list[Net]:
        """Every net an instance output or an assignment drives."""
        nets = [
            net
            for _, entity, connections in self.netlist.instances()
            for port in entity.ports
            if port.mode is Direction.OUT and (net := connections[port.name]) is not None
        ]
        return nets + [target for target, _ in self.netlist.assignments()]

    def _join_parts(self) -> None:
        """A vector driven part by part: a signal per part, joined into the whole."""
        by_signal: dict[str, list[Net]] = {}
        for net in self._driven():
            if net.signal is not None and net.text != net.signal:
                by_signal.setdefault(net.signal, []).append(net)
        for name, nets in by_signal.items():
            nets.sort(key=lambda n: n.span[1], reverse=True)
            for net in nets:
                self.parts[net.text] = _signal(net.bits, net.wire)
            whole = [self.parts[n.text] for n in nets]
            joined = ConcatSignal(*whole) if len(whole) > 1 else whole[0]
            self.processes.append((follow, {"target": self.signals[name], "source": joined}))

    def read(self, net: Net) -> Any:
        """The signal that carries `net` to an input."""
        if net.signal is None:  # a constant
            value = int(net.text.strip("'\""), 2)
            return Signal(bool(value)) if net.wire else Signal(intbv(value)[net.bits :])
        whole = self.signals[net.signal]
        if net.text == net.signal:
            return whole
        if net.text.startswith("not "):
            inverted = _signal(1, True)
            self.processes.append((_invert, {"target": inverted, "source": whole}))
            return inverted
        high, low = net.span
        return whole(low) if net.wire else whole(high + 1, low)

    def write(self, net: Net) -> Any:
        """The signal an output drives for `net`."""
        assert net.signal is not None
        return self.parts.get(net.text, self.signals[net.signal])

    def plan(self, blocks: Mapping[str, Block]) -> list[tuple[Block, dict[str, Any]]]:
        """Every instance to create: its block and its arguments."""
        for target, source in self.netlist.assignments():
            copy = {"target": self.write(target), "source": self.read(source)}
            self.processes.append((follow, copy))
        for _, entity, connections in self.netlist.instances():
            arguments = {}
            for port in entity.ports:
                net = connections[port.name]
                if net is None:  # an open output
                    arguments[port.name] = _signal(port.bits, port.wire)
                elif port.mode is Direction.OUT:
                    arguments[port.name] = self.write(net)
                else:
                    arguments[port.name] = self.read(net)
            self.processes.append((blocks[entity.name], arguments))
        return self.processes
