"""A small builder of structural HDL: entities wired together by typed, width-checked nets.

The system's top level only instantiates generated entities (manager, converters, scheduler,
accelerator wrappers) and connects their ports, so it is built as data — ports, signals,
instances, assignments — and checked before it is rendered: every input of every instance is
driven exactly once, widths and kinds (``std_logic`` vs ``std_logic_vector``) agree, and no
signal has two drivers. The same netlist renders as VHDL-2008 with direct entity instantiation
(`Netlist.render`) and as Verilog-2001 with the same module, port and signal names
(`Netlist.render_verilog`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field

from rfc.lib.converters.ports import Direction

_IDENTIFIER = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_INVERSION = re.compile(r"^not (\w+)$")


@dataclass(frozen=True)
class PortDecl:
    """A port of an entity.

    Attributes:
        name: VHDL identifier.
        mode: Direction.
        bits: Width.
        wire: ``std_logic`` when true (then `bits` is 1), else ``std_logic_vector``.
    """

    name: str
    mode: Direction
    bits: int
    wire: bool = False


@dataclass(frozen=True)
class EntityDecl:
    """The interface of an entity the netlist instantiates (or the netlist's own).

    Attributes:
        name: Entity name.
        ports: Its ports.
        vlnv: For a vendor IP core (a Vitis HLS export): its IP identifier. Its VHDL is not
            generated, so it is instantiated through a component declaration — the netlist
            analyses without it — and the block design makes it an IP cell.
    """

    name: str
    ports: tuple[PortDecl, ...]
    vlnv: str | None = None

    def port(self, name: str) -> PortDecl:
        """The port called `name`."""
        for port in self.ports:
            if port.name == name:
                return port
        raise KeyError(f"entity {self.name} has no port {name}")


@dataclass(frozen=True)
class Net:
    """A value that can drive a port or be driven: a signal, a slice, a bit or a constant.

    Attributes:
        text: Its VHDL expression.
        bits: Width.
        wire: Whether it is a ``std_logic``.
        signal: The signal it reads or drives (None for constants).
        span: The bits of `signal` it covers, ``(high, low)``.
    """

    text: str
    bits: int
    wire: bool
    signal: str | None = None
    span: tuple[int, int] = (0, 0)

    @property
    def verilog(self) -> str:
        """The same value as a Verilog expression."""
        if self.signal is None:  # a constant: '1' or "0101"
            return f"{self.bits}'b{self.text.strip(chr(39) + chr(34))}"
        name = _verilog_identifier(self.signal)
        if self.text.startswith("not "):
            return f"~{name}"
        if self.text == self.signal:
            return name
        high, low = self.span
        return f"{name}[{low}]" if self.wire else f"{name}[{high}:{low}]"

    def bit(self, index: int) -> Net:
        """One bit of a vector, as a ``std_logic``."""
        if self.wire or not 0 <= index < self.bits or self.signal is None:
            raise ValueError(f"no bit {index} in {self.text}")
        low = self.span[1] + index
        return Net(f"{self.signal}({low})", 1, True, self.signal, (low, low))

    def slice(self, high: int, low: int) -> Net:
        """Bits `high` down to `low` of a vector, as a vector."""
        if self.wire or not 0 <= low <= high < self.bits or self.signal is None:
            raise ValueError(f"no bits {high}..{low} in {self.text}")
        base = self.span[1]
        return Net(
            f"{self.signal}({base + high} downto {base + low})",
            high - low + 1,
            False,
            self.signal,
            (base + high, base + low),
        )


def constant(value: int, bits: int, wire: bool = False) -> Net:
    """A constant: a ``'0'``/``'1'`` wire or a vector literal."""
    if wire:
        return Net(f"'{value & 1}'", 1, True)
    return Net(f'"{value:0{bits}b}"', bits, False)


@dataclass
class _Instance:
    label: str
    entity: EntityDecl
    connections: dict[str, Net | None]
    generics: dict[str, int] = field(default_factory=dict)


class NetlistError(ValueError):
    """The netlist is wired wrongly: a bug in the generator that builds it."""


class Netlist:
    """A structural VHDL entity under construction.

    Args:
        entity: The netlist's own name and ports.
        comment: Lines written at the top of the file.
    """

    def __init__(self, entity: EntityDecl, comment: str = "") -> None:
        self.entity = entity
        self.comment = comment
        self._signals: dict[str, tuple[int, bool]] = {}
        self._instances: list[_Instance] = []
        self._assignments: list[tuple[Net, Net]] = []
        for port in entity.ports:
            _check_identifier(port.name)
            self._signals[port.name] = (port.bits, port.wire)

    def port(self, name: str) -> Net:
        """A port of the netlist itself, as a net."""
        port = self.entity.port(name)
        return Net(name, port.bits, port.wire, name, (port.bits - 1, 0))

    def signal(self, name: str, bits: int = 1, wire: bool = False) -> Net:
        """Declare an internal signal."""
        _check_identifier(name)
        if name.lower() in {n.lower() for n in self._signals}:
            raise NetlistError(f"signal {name} declared twice")
        self._signals[name] = (bits, wire)
        return Net(name, bits, wire, name, (bits - 1, 0))

    def instance(
        self,
        label: str,
        entity: EntityDecl,
        connections: Mapping[str, Net | None],
        generics: Mapping[str, int] | None = None,
    ) -> None:
        """Instantiate `entity`; every port must be named, an unused output maps to None.

        Raises:
            NetlistError: A port is missing, unknown, an unconnected input, or mismatched.
        """
        _check_identifier(label)
        names = {p.name for p in entity.ports}
        if unknown := sorted(set(connections) - names):
            raise NetlistError(f"{label}: {entity.name} has no port {unknown[0]}")
        if missing := [p.name for p in entity.ports if p.name not in connections]:
            raise NetlistError(f"{label}: port {missing[0]} of {entity.name} is not connected")
        for port in entity.ports:
            net = connections[port.name]
            if net is None:
                if port.mode is Direction.IN:
                    raise NetlistError(f"{label}: input {port.name} must be driven")
                continue
            if net.bits != port.bits or net.wire != port.wire:
                raise NetlistError(
                    f"{label}.{port.name}: {_kind(port.bits, port.wire)} port connected to "
                    f"{net.text} ({_kind(net.bits, net.wire)})"
                )
        self._instances.append(_Instance(label, entity, dict(connections), dict(generics or {})))

    def assign(self, target: Net, source: Net | str) -> None:
        """A concurrent assignment ``target <= source``.

        `source` may also be the inversion of a declared ``std_logic``, such as
        ``not aresetn``.
        """
        if isinstance(source, str):
            source = self._inversion(source)
        if source.bits != target.bits or source.wire != target.wire:
            raise NetlistError(f"{target.text} <= {source.text}: widths or kinds differ")
        self._assignments.append((target, source))

    def _inversion(self, text: str) -> Net:
        match = _INVERSION.match(text)
        if match is None or self._signals.get(match.group(1)) != (1, True):
            raise NetlistError(f"'{text}' is not the inversion of a std_logic signal")
        name = match.group(1)
        return Net(text, 1, True, name, (0, 0))

    def instances(self) -> Iterator[tuple[str, EntityDecl, Mapping[str, Net | None]]]:
        """Each instance's label, entity and port connections, in the order they were added."""
        for instance in self._instances:
            yield instance.label, instance.entity, instance.connections

    def assignments(self) -> tuple[tuple[Net, Net], ...]:
        """The concurrent assignments ``(target, source)``."""
        return tuple(self._assignments)

    def check(self) -> None:
        """Every signal bit has exactly one driver and every netlist output is driven.

        Raises:
            NetlistError: A bit with no driver or with two.
        """
        drivers: dict[tuple[str, int], str] = {}

        def drive(net: Net, by: str) -> None:
            if net.signal is None:
                raise NetlistError(f"{by} drives a constant")
            for bit in range(net.span[1], net.span[0] + 1):
                key = (net.signal, bit)
                if key in drivers:
                    raise NetlistError(f"{net.signal}({bit}) driven by {drivers[key]} and {by}")
                drivers[key] = by

        for port in self.entity.ports:
            if port.mode is Direction.IN:
                drive(self.port(port.name), "the port")
        for instance in self._instances:
            for port in instance.entity.ports:
                net = instance.connections[port.name]
                if port.mode is Direction.OUT and net is not None:
                    drive(net, f"{instance.label}.{port.name}")
        for target, _ in self._assignments:
            drive(target, f"assignment to {target.text}")
        for name, (bits, _) in self._signals.items():
            for bit in range(bits):
                if (name, bit) not in drivers:
                    raise NetlistError(f"{name}({bit}) has no driver")

    def render(self) -> str:
        """The VHDL text (checks first)."""
        self.check()
        lines = [f"-- {line}" for line in self.comment.splitlines()]
        lines += ["library ieee;", "use ieee.std_logic_1164.all;", ""]
        lines.append(f"entity {self.entity.name} is")
        lines += _port_clause(self.entity.ports)
        lines.append(f"end entity {self.entity.name};")
        lines += ["", f"architecture structure of {self.entity.name} is"]
        ports = {p.name for p in self.entity.ports}
        for name, (bits, wire) in self._signals.items():
            if name not in ports:
                lines.append(f"  signal {name} : {_kind(bits, wire)};")
        cores = {i.entity.name: i.entity for i in self._instances if i.entity.vlnv}
        for core in cores.values():
            lines += [f"  component {core.name} is", *_port_clause(core.ports), "  end component;"]
        lines.append("begin")
        for target, source in self._assignments:
            lines.append(f"  {target.text} <= {source.text};")
        for instance in self._instances:
            lines.append("")
            unit = instance.entity.name
            lines.append(
                f"  {instance.label} : {unit if instance.entity.vlnv else 'entity work.' + unit}"
            )
            if instance.generics:
                generics = ", ".join(f"{k} => {v}" for k, v in instance.generics.items())
                lines.append(f"    generic map ({generics})")
            lines.append("    port map (")
            maps = [
                f"      {name} => {'open' if net is None else net.text}"
                for name, net in instance.connections.items()
            ]
            lines.append(",\n".join(maps))
            lines.append("    );")
        lines += ["end architecture structure;", ""]
        return "\n".join(lines)

    def render_verilog(self) -> str:
        """The Verilog text (checks first): the same module, ports, wires and instances."""
        self.check()
        lines = [f"// {line}" for line in self.comment.splitlines()]
        ports = {p.name for p in self.entity.ports}
        lines += ["`default_nettype none", "", f"module {_verilog_identifier(self.entity.name)} ("]
        lines.append(
            ",\n".join(
                f"    {p.mode.value}put wire{_range(p.bits, p.wire)} {_verilog_identifier(p.name)}"
                for p in self.entity.ports
            )
        )
        lines.append(");")
        for name, (bits, wire) in self._signals.items():
            if name not in ports:
                lines.append(f"  wire{_range(bits, wire)} {_verilog_identifier(name)};")
        for target, source in self._assignments:
            lines.append(f"  assign {target.verilog} = {source.verilog};")
        for instance in self._instances:
            lines += ["", f"  {_verilog_identifier(instance.entity.name)}"]
            if instance.generics:
                generics = ", ".join(f".{k}({v})" for k, v in instance.generics.items())
                lines.append(f"    #({generics})")
            lines.append(f"    {_verilog_identifier(instance.label)} (")
            maps = [
                f"      .{_verilog_identifier(name)}({'' if net is None else net.verilog})"
                for name, net in instance.connections.items()
            ]
            lines.append(",\n".join(maps))
            lines.append("    );")
        lines += ["endmodule", "", "`default_nettype wire", ""]
        return "\n".join(lines)


def _range(bits: int, wire: bool) -> str:
    return "" if wire else f" [{bits - 1}:0]"


#: Verilog-2005 keywords, which are legal VHDL identifiers but must be escaped in Verilog.
_VERILOG_KEYWORDS = frozenset(
    re.findall(
        r"\w+",
        """always and assign automatic begin buf bufif0 bufif1 case casex casez cell cmos config
    deassign default defparam design disable edge else end endcase endconfig endfunction
    endgenerate endmodule endprimitive endspecify endtable endtask event for force forever fork
    function generate genvar highz0 highz1 if ifnone incdir include initial inout input instance
    integer join large liblist library localparam macromodule medium module nand negedge nmos nor
    noshowcancelled not notif0 notif1 or output parameter pmos posedge primitive pull0 pull1
    pulldown pullup pulsestyle_ondetect pulsestyle_onevent rcmos real realtime reg release repeat
    rnmos rpmos rtran rtranif0 rtranif1 scalared showcancelled signed small specify specparam
    strong0 strong1 supply0 supply1 table task time tran tranif0 tranif1 tri tri0 tri1 triand
    trior trireg unsigned use uwire vectored wait wand weak0 weak1 while wire wor xnor xor""",
    )
)


def _verilog_identifier(name: str) -> str:
    """`name` in Verilog: escaped (the same name to every tool) when it is a keyword."""
    return f"\\{name} " if name in _VERILOG_KEYWORDS else name


def _port_clause(ports: Iterable[PortDecl]) -> list[str]:
    entries = [f"    {p.name} : {p.mode.value} {_kind(p.bits, p.wire)}" for p in ports]
    if not entries:
        return []
    return ["  port (", ";\n".join(entries), "  );"]


def _kind(bits: int, wire: bool) -> str:
    return "std_logic" if wire else f"std_logic_vector({bits - 1} downto 0)"


def _check_identifier(name: str) -> None:
    if not _IDENTIFIER.match(name) or "__" in name or name.endswith("_"):
        raise NetlistError(f"'{name}' is not a VHDL identifier")
