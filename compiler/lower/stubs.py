"""`rfc stub`: a ready-to-fill skeleton of one accelerator, typed from its message signatures.

Every port of every message comes from the signature (`rfc.lower.system.interfaces`), so the
skeleton has exactly the ports, members and widths `rfc build` will check. The MyHDL form takes
interface objects; the VHDL form flat ports; the HLS form the message structs rfc generates and
the top function taking them; the Python form is a ROS-SW function (which is also the shape of a
reference model). Each skeleton converts and builds as it is: inputs are
accepted and dropped, outputs stay idle, until the user writes the logic.
"""

from __future__ import annotations

import textwrap
from collections.abc import Iterator, Sequence
from dataclasses import replace
from enum import StrEnum

from rfc.errors import RfcError, did_you_mean
from rfc.hls.c_types import hls_stub, message_structs
from rfc.hls.ports import logic_refusal
from rfc.ir.model import AcceleratorType, Block, Design, Direction
from rfc.ir.model import Port as ModelPort
from rfc.lib.converters.ports import PortRole, member_text
from rfc.lower.hls_headers import port_signatures
from rfc.lower.system.interfaces import Pin, accelerator_pins
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.passes.base import types_of


class StubLanguage(StrEnum):
    """What the skeleton is written in."""

    MYHDL = "myhdl"
    VHDL = "vhdl"
    HLS = "hls"
    PYTHON = "python"


#: Pins an accelerator drives on an input port: the handshakes' readies.
_READIES = frozenset({PortRole.READY, PortRole.TREADY})
_FLOATS = frozenset({"float32", "float64"})


def accelerator_stub(design: Design, name: str, language: StubLanguage) -> str:
    """The skeleton of accelerator type (or block) `name` of a compiled design.

    Raises:
        RfcError: No accelerator type or block has that name, or no block uses the type.
    """
    accelerator, block = _find(design, name)
    width, limits = design.project.bus_width, design.project.maxima
    ports = [(port, accelerator_pins(port, width, limits)) for port in block.ports]
    if language is StubLanguage.VHDL:
        return _vhdl(accelerator, ports)
    if language is StubLanguage.HLS:
        return _hls(design, accelerator, block)
    # A ROS-SW accelerator runs the function named like its top (docs/runtime.md).
    software = language is StubLanguage.PYTHON
    function = _function_name(accelerator) + ("" if software else "_reference")
    reference = _reference(accelerator, block, types_of(design.project), design, function)
    imports = [_REFERENCE_IMPORT]
    if language is StubLanguage.MYHDL:
        imports.insert(0, "from myhdl import always_seq, block")
        code = [_myhdl(accelerator, ports), reference]
    else:
        code = [reference]
    kind = "MyHDL accelerator" if language is StubLanguage.MYHDL else "ROS-SW accelerator"
    title = f'"""{accelerator.name}: a {kind} with its reference (skeleton written by rfc stub)."""'
    return "\n".join([title, "", *imports, "", "", "\n\n".join(code)])


_REFERENCE_IMPORT = "from rfc.messages.rosbags_adapter import message_types"


def _find(design: Design, name: str) -> tuple[AcceleratorType, Block]:
    types = {a.name: a for a in design.accelerators}
    blocks = {b.name: b for b in design.blocks if b.accelerator is not None}
    if name in blocks:
        return types[blocks[name].accelerator or ""], blocks[name]
    if name not in types:
        raise RfcError(
            f"the spec has no accelerator type or accelerator block '{name}'",
            hint=did_you_mean(name, [*types, *blocks])
            or f"accelerator types: {', '.join(types) or 'none'}",
        )
    block = next((b for b in blocks.values() if b.accelerator == name), None)
    if block is None:
        raise RfcError(
            f"no block of the spec uses accelerator type '{name}', so its ports have no "
            "selected fields yet",
            location=types[name].location,
            hint=f"add a block of type {name} with its connections",
        )
    return types[name], block


def _function_name(accelerator: AcceleratorType) -> str:
    return accelerator.top or accelerator.name


def _member(port: str, pin: Pin) -> str:
    return member_text(port, pin.signal.member)


def _describe(pin: Pin) -> str:
    """What a pin carries, in words."""
    role, signal = pin.role, pin.signal
    if role is PortRole.FIELD:
        ros = signal.ros_type or ""
        if ros in _FLOATS:
            return f"{ros}, its {pin.port.bits}-bit IEEE-754 pattern ({signal.path})"
        if ros == "bool":
            return f"bool, 1 bit ({signal.path})"
        return f"{ros}, {pin.port.bits} bits ({signal.path})"
    if role in (PortRole.LENGTH, PortRole.COUNT):
        unit = "characters" if role is PortRole.LENGTH else "elements"
        return f"{unit} of {signal.path} ({signal.ros_type}), known before the first"
    if role is PortRole.TDATA:
        return f"a beat of {signal.path}: {pin.port.bits // 8} bytes, elements in order"
    if role is PortRole.TKEEP:
        return "which bytes of the beat are valid"
    if role is PortRole.LAST:
        return "the last element"
    if role is PortRole.TLAST:
        return "the last beat"
    what = "message" if pin.group == "msg" else pin.group
    return f"{role.value.removeprefix('t')} of the {what}"


def _myhdl(accelerator: AcceleratorType, ports: Sequence[tuple[ModelPort, tuple[Pin, ...]]]) -> str:
    name = _function_name(accelerator)
    arguments = ", ".join(["clk", "rst", *(port.name for port, _ in ports)])
    lines = [
        "@block",
        f"def {name}({arguments}):",
        f'    """{_summary(ports)}',
        "",
        "    Args:",
        "        clk: The clock; rfc samples every signal on its rising edge.",
        "        rst: Synchronous reset, active high.",
    ]
    for port, pins in ports:
        way = "in" if port.direction is Direction.IN else "out"
        lines.append(f"        {port.name}: {_message(port)} {way}:")
        lines += [f"            {_member(port.name, pin)}: {_describe(pin)}" for pin in pins]
    lines += ['    """']
    bindings, body = _idle_logic(ports)
    lines += [f"    {line}" for line in bindings]
    lines += [
        "",
        "    @always_seq(clk.posedge, reset=rst)",
        "    def logic():",
        "        # TODO: the accelerator. As generated, it takes every input and sends nothing.",
        *(f"        {line}" for line in body),
        "",
        "    return logic",
    ]
    return "\n".join(lines) + "\n"


def _idle_logic(
    ports: Sequence[tuple[ModelPort, tuple[Pin, ...]]],
) -> tuple[list[str], list[str]]:
    """Bindings at elaboration and generator statements: readies high, outputs idle."""
    bindings: list[str] = []
    body: list[str] = []
    loops: set[str] = set()
    for port, pins in ports:
        for pin in pins:
            if pin.port.mode.value != "out":
                continue
            value = "1" if pin.role in _READIES else "0"
            member = pin.signal.member
            indices = [i for i, step in enumerate(member) if isinstance(step, int)]
            if indices and indices[-1] == len(member) - 1 and len(indices) == 1:
                array = _member(port.name, _cut(pin, len(member) - 1))
                if array not in loops:
                    loops.add(array)
                    size = 1 + max(
                        int(p.signal.member[-1])
                        for p in pins
                        if p.signal.member[:-1] == member[:-1]
                    )
                    body += [f"for i in range({size}):", f"    {array}[i].next = {value}"]
                continue
            target = _member(port.name, pin)
            if indices:  # MyHDL follows no attribute of a list element inside a generator
                local = "_".join(str(step) for step in (port.name, *member))
                bindings.append(f"{local} = {target}")
                target = local
            body.append(f"{target}.next = {value}")
    return bindings, body


def _cut(pin: Pin, length: int) -> Pin:
    return replace(pin, signal=replace(pin.signal, member=pin.signal.member[:length]))


def _message(port: ModelPort) -> str:
    assert port.layout is not None
    return port.layout.display_name


def _summary(ports: Sequence[tuple[ModelPort, tuple[Pin, ...]]]) -> str:
    inputs = ", ".join(f"{_message(p)} {p.name}" for p, _ in ports if p.direction is Direction.IN)
    outputs = ", ".join(f"{_message(p)} {p.name}" for p, _ in ports if p.direction is Direction.OUT)
    return f"{inputs or 'nothing'} in, {outputs or 'nothing'} out."


def _vhdl(accelerator: AcceleratorType, ports: Sequence[tuple[ModelPort, tuple[Pin, ...]]]) -> str:
    entity = _function_name(accelerator).lower()
    declarations = ["clk : in std_logic;  -- rising edge", "rst : in std_logic;  -- synchronous"]
    assignments = []
    for port, pins in ports:
        way = "in" if port.direction is Direction.IN else "out"
        declarations.append(f"-- {port.name}: {_message(port)} {way}")
        for pin in pins:
            decl = pin.port
            kind = "std_logic" if decl.wire else f"std_logic_vector({decl.bits - 1} downto 0)"
            declarations.append(
                f"{decl.name} : {decl.mode.value} {kind};  -- {_member(port.name, pin)}: "
                f"{_describe(pin)}"
            )
            if decl.mode.value == "out":
                one = "'1'" if pin.role in _READIES else "'0'"
                value = one if decl.wire else "(others => '0')"
                assignments.append(f"  {decl.name} <= {value};")
    # The last declaration has no semicolon: move it behind the comment's start.
    last = max(i for i, line in enumerate(declarations) if not line.startswith("--"))
    code, _, comment = declarations[last].partition(";  --")
    declarations[last] = f"{code}  --{comment}"
    lines = [
        f"-- {accelerator.name}: a VHDL accelerator (skeleton written by rfc stub).",
        "-- As generated it takes every input and sends nothing: write the architecture.",
        "library ieee;",
        "use ieee.std_logic_1164.all;",
        "use ieee.numeric_std.all;",
        "",
        f"entity {entity} is",
        "  port (",
        *(f"    {line}" for line in declarations),
        "  );",
        f"end entity {entity};",
        "",
        f"architecture rtl of {entity} is",
        "begin",
        *assignments,
        "end architecture rtl;",
    ]
    return "\n".join(lines) + "\n"


def _hls(design: Design, accelerator: AcceleratorType, block: Block) -> str:
    """The top function to fill in, on the message structs of the header rfc generates."""
    signatures, directions = port_signatures(design, block)
    name, top = accelerator.name, _function_name(accelerator)
    structs = message_structs(signatures, directions)  # refuses what no struct can carry
    refusals = [
        line
        for port, pins in signatures.items()
        if (refusal := logic_refusal(port, pins)) is not None
        for line in _comment(f"Not for the logic as selected: {refusal.message}; {refusal.hint}.")
    ]
    return (
        f"// {name}: an HLS accelerator (skeleton written by rfc stub). rfc build writes\n"
        f"// {name}_messages.h into hls/, and rfc sim compiles against it (C simulation).\n"
        + "".join(refusals)
        + hls_stub(name, structs, top)
    )


def _comment(text: str, width: int = 96) -> list[str]:
    """`text` as C++ comment lines of at most `width` characters."""
    return [f"// {line}\n" for line in textwrap.wrap(text, width - 3)]


def _reference(
    accelerator: AcceleratorType, block: Block, types: MessageTypes, design: Design, name: str
) -> str:
    inputs = [p.name for p in block.inputs]
    outputs = [
        f'types.build("{p.message}", {_defaults(types, p.message or "")})' for p in block.outputs
    ]
    result = outputs[0] if len(outputs) == 1 else f"({', '.join(outputs)})"
    project = design.project
    paths = ", ".join(f'"{p}"' for p in project.msg_paths)
    lines = [
        f"def {name}({', '.join(inputs)}):",
        f'    """{accelerator.name} on rosbags messages: the reference, or the ROS-SW function.',
        "",
        "    Takes one message object per input port and returns one per output port (a tuple",
        "    for several, None for no message this time).",
        '    """',
        f'    types = message_types("{project.middleware.value}", "{project.distro}"'
        + (f", ({paths},))" if paths else ")"),
        "    # TODO: compute the outputs from the inputs.",
        f"    return {result}",
    ]
    return "\n".join(lines) + "\n"


def _defaults(types: MessageTypes, canonical: str) -> str:
    """A Python literal of `canonical`'s fields at their default values (``build``'s tree)."""
    return "{" + ", ".join(_field_defaults(types, canonical)) + "}"


def _field_defaults(types: MessageTypes, canonical: str) -> Iterator[str]:
    for field in types.fields(canonical):
        if field.is_sequence:
            value = "[]"
        else:
            if field.is_message:
                one = _defaults(types, field.base)
            elif field.base == "string":
                one = '""'
            elif field.base == "bool":
                one = "False"
            elif field.base in _FLOATS:
                one = "0.0"
            else:
                one = "0"
            value = one if field.array_length is None else f"[{one}] * {field.array_length}"
        yield f'"{field.name}": {value}'
