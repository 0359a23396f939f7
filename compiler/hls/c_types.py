"""The C++ side of an HLS accelerator's messages: one struct per message port, and streams.

An HLS top function takes, per port in declaration order, the port's struct (inputs by value,
outputs by pointer) followed by one ``hls::stream<T>`` reference per string or variable
sequence of the port, in the order `rfc msg show` lists them. The struct mirrors the selected
fields of the message (`rfc.lib.converters.ports`): sub-messages are nested structs, fixed
arrays C arrays, and the length of each stream is a field beside where the stream would be
(``data_length`` for ``data``), so the function knows it before reading the first element.
C types come from ROS types (`CTYPES`); a string is a stream of ``char``, a sequence of
messages a stream of element structs (whose fields are all fixed-size).

With ``#pragma HLS DISAGGREGATE`` Vitis HLS flattens a struct argument into one port per member
named ``<arg>_<member>`` (``rgb_header_stamp_sec``), which are the names the message signature
gives the same fields.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from rfc.errors import RfcError
from rfc.ir.model import Direction
from rfc.lib.converters.ports import Port, PortRole
from rfc.lib.converters.steps import ROOT

#: C type of each ROS primitive (``<cstdint>`` types; ROS 2 ``char`` and ``byte`` are bytes).
CTYPES = {
    "bool": "bool",
    "byte": "uint8_t",
    "char": "uint8_t",
    "float32": "float",
    "float64": "double",
    **{f"{sign}int{bits}": f"{sign}int{bits}_t" for sign in ("", "u") for bits in (8, 16, 32, 64)},
}
#: C type of a stream or sequence length.
LENGTH_CTYPE = "uint32_t"
#: What a string's characters are in C.
CHAR_CTYPE = "char"

_CPP_KEYWORDS = frozenset(
    [
        "alignas",
        "alignof",
        "and",
        "and_eq",
        "asm",
        "auto",
        "bitand",
        "bitor",
        "bool",
        "break",
        "case",
        "catch",
        "char",
        "char16_t",
        "char32_t",
        "class",
        "compl",
        "const",
        "constexpr",
        "const_cast",
        "continue",
        "decltype",
        "default",
        "delete",
        "do",
        "double",
        "dynamic_cast",
        "else",
        "enum",
        "explicit",
        "export",
        "extern",
        "false",
        "float",
        "for",
        "friend",
        "goto",
        "if",
        "inline",
        "int",
        "long",
        "mutable",
        "namespace",
        "new",
        "noexcept",
        "not",
        "not_eq",
        "nullptr",
        "operator",
        "or",
        "or_eq",
        "private",
        "protected",
        "public",
        "register",
        "reinterpret_cast",
        "return",
        "short",
        "signed",
        "sizeof",
        "static",
        "static_assert",
        "static_cast",
        "struct",
        "switch",
        "template",
        "this",
        "thread_local",
        "throw",
        "true",
        "try",
        "typedef",
        "typeid",
        "typename",
        "union",
        "unsigned",
        "using",
        "virtual",
        "void",
        "volatile",
        "wchar_t",
        "while",
        "xor",
        "xor_eq",
    ]
)


# A few fields and a property, like rfc.lib.converters.frame_length's records in shape only.
@dataclass(frozen=True)
class CField:
    """One scalar of a struct, in declaration order.

    Attributes:
        member: Its place in the struct (names and array indices).
        ctype: Its C type.
        ros_type: The ROS type it carries (``uint32``; ``string``/``uint8[]`` for a length).
        path: The message field it carries (for a length: the string or sequence's path).
        length: Whether it is the length of a stream.
    """

    member: tuple[str | int, ...]
    ctype: str
    ros_type: str
    path: str
    length: bool = False

    @property
    def access(self) -> str:
        """C++ access to it from its struct: ``.header.stamp.sec``, ``.vertex_indices[2]``."""
        return "".join(f"[{s}]" if isinstance(s, int) else f".{s}" for s in self.member)


@dataclass(frozen=True)
class CStream:
    """One ``hls::stream`` argument of a port.

    Attributes:
        argument: Its argument name (``rgb_data``).
        path: The string or sequence it carries.
        ros_type: Its ROS type (``string``, ``uint8[]``, ``geometry_msgs/msg/Point32[]``).
        element: The C type of one element (a struct name for a sequence of messages).
        length: The struct field holding its length.
        fields: For a sequence of messages: the element struct's fields (members relative to
            the element, paths relative to the element's message).
    """

    argument: str
    path: str
    ros_type: str
    element: str
    length: CField
    fields: tuple[CField, ...] = ()


@dataclass(frozen=True)
class MessageStruct:
    """The C++ view of one message port: its struct and its streams.

    Attributes:
        port: The accelerator's port name (the argument's name).
        output: An output port (the function fills the struct through a pointer).
        type_name: The struct's type name (``<port>_t``).
        fields: The struct's scalars in declaration order.
        streams: The port's streams in argument order.
    """

    port: str
    output: bool
    type_name: str
    fields: tuple[CField, ...]
    streams: tuple[CStream, ...]

    def arguments(self) -> tuple[str, ...]:
        """The port's arguments as the top function declares them."""
        struct = (
            f"{self.type_name} *{self.port}" if self.output else f"{self.type_name} {self.port}"
        )
        return (struct, *(f"hls::stream<{s.element}> &{s.argument}" for s in self.streams))


def message_struct(port: str, ports: tuple[Port, ...], output: bool) -> MessageStruct:
    """Read one port's message signature as a struct and streams.

    Args:
        port: The accelerator's port name.
        ports: Its signature (`rfc.lib.converters.ports.accelerator_signature`).
        output: Whether the accelerator sends on it.

    Raises:
        RfcError: A field that C++ cannot name, or a stream HLS accelerators do not take.
    """
    fields: list[CField] = []
    streams: list[CStream] = []
    for signal in ports:
        if signal.role is PortRole.FIELD and signal.group == ROOT:
            fields.append(_field(port, signal.member, signal))
        elif signal.role in (PortRole.LENGTH, PortRole.COUNT):
            stream = _stream(port, signal, ports)
            fields.append(stream.length)
            streams.append(stream)
    return MessageStruct(port, output, f"{port}_t", tuple(fields), tuple(streams))


def _stream(port: str, signal: Port, ports: tuple[Port, ...]) -> CStream:
    """The stream of a string or sequence, from its length port."""
    if signal.group != ROOT:
        raise _refusal(port, signal, "a string or sequence inside a sequence's elements")
    member = signal.member[:-1]
    _check_names(port, signal, member)
    ros_type = signal.ros_type or ""
    path = signal.path or ""
    length = CField((*member[:-1], f"{member[-1]}_length"), LENGTH_CTYPE, ros_type, path, True)
    argument = "_".join(str(s) for s in (port, *member))
    element_type = ros_type.partition("[")[0]
    if signal.role is PortRole.LENGTH:
        return CStream(argument, path, ros_type, CHAR_CTYPE, length)
    if element_type.startswith("string"):
        raise _refusal(port, signal, "a sequence of strings")
    if element_type in CTYPES:
        return CStream(argument, path, ros_type, CTYPES[element_type], length)
    element = tuple(
        _field(port, p.member[len(member) :], p, prefix=f"{path}.")
        for p in ports
        if p.role is PortRole.FIELD and p.group != ROOT and p.member[: len(member)] == member
    )
    return CStream(argument, path, ros_type, f"{argument}_t", length, element)


def _field(port: str, member: tuple[str | int, ...], signal: Port, prefix: str = "") -> CField:
    _check_names(port, signal, member)
    ros_type = signal.ros_type or ""
    ctype = CTYPES.get(ros_type)
    if ctype is None:
        raise _refusal(port, signal, f"a field of type {ros_type}")
    return CField(member, ctype, ros_type, (signal.path or "").removeprefix(prefix))


def _check_names(port: str, signal: Port, member: tuple[str | int, ...]) -> None:
    for step in member:
        if isinstance(step, str) and step.rstrip("_") in _CPP_KEYWORDS:
            raise RfcError(
                f"field '{signal.path}' of port '{port}' is named '{step.rstrip('_')}', a C++ "
                "keyword, so it cannot be a member of the port's HLS struct",
                hint=f"exclude '{signal.path}' from port '{port}', or write the accelerator in "
                "MyHDL or VHDL",
            )


def _refusal(port: str, signal: Port, what: str) -> RfcError:
    return RfcError(
        f"port '{port}' carries {what} ('{signal.path}'), which HLS accelerators do not take",
        hint=f"exclude '{signal.path}' from port '{port}', or write the accelerator in MyHDL or "
        "VHDL",
    )


def message_structs(
    ports: Mapping[str, tuple[Port, ...]], directions: Mapping[str, Direction]
) -> tuple[MessageStruct, ...]:
    """The struct of every port, in the order of `ports` (inputs first, as declared).

    Args:
        ports: Per port, its message signature (the ``signal`` of its
            `rfc.lower.system.interfaces.accelerator_pins`).
        directions: Per port, whether the accelerator receives (IN) or sends (OUT) on it.

    Raises:
        RfcError: A field the struct convention cannot carry.
    """
    return tuple(
        message_struct(name, signals, directions[name] is Direction.OUT)
        for name, signals in ports.items()
    )


def hls_header(
    accelerator_name: str, structs: tuple[MessageStruct, ...], top: str | None = None
) -> str:
    """The ``<accelerator>_messages.h`` an HLS accelerator includes.

    Args:
        accelerator_name: The accelerator type's name.
        structs: Its ports' structs, as `message_structs` gives them.
        top: The top function's name, when it is not the accelerator's.

    Returns:
        The header: the structs, and the top function's declaration.
    """
    guard = f"RFC_{accelerator_name.upper()}_MESSAGES_H"
    lines = [
        f"// The messages of HLS accelerator {accelerator_name}, generated by rfc. Do not edit.",
        f"#ifndef {guard}",
        f"#define {guard}",
        "",
        "#include <cstdint>",
        "",
        "#include <hls_stream.h>",
        "",
    ]
    for struct in structs:
        lines += _definitions(struct)
    lines += [*_declaration(top or accelerator_name, structs, ";"), "", f"#endif  // {guard}", ""]
    return "\n".join(lines)


def hls_stub(
    accelerator_name: str, structs: tuple[MessageStruct, ...], top: str | None = None
) -> str:
    """A ready-to-fill ``.cpp`` of the top function, every field commented with its ROS type.

    Args are those of `hls_header`: the stub is the .cpp that includes that header.
    """
    lines = [f'#include "{accelerator_name}_messages.h"', ""]
    lines += _declaration(top or accelerator_name, structs, " {")
    lines.append("#pragma HLS INTERFACE mode=ap_ctrl_hs port=return")
    for struct in structs:
        lines.append(f"#pragma HLS DISAGGREGATE variable={struct.port}")
        mode = "ap_vld" if struct.output else "ap_none"
        lines.append(f"#pragma HLS INTERFACE mode={mode} port={struct.port}")
        lines += [f"#pragma HLS INTERFACE mode=ap_fifo port={s.argument}" for s in struct.streams]
    for struct in structs:
        arrow = "->" if struct.output else "."
        verb = "set" if struct.output else "read"
        lines.append(f"    // {struct.port} ({'output' if struct.output else 'input'}): {verb}")
        for field in struct.fields:
            what = f"length of {field.path}" if field.length else field.path
            lines.append(
                f"    //   {struct.port}{arrow}{field.access[1:]}: {field.ros_type} ({what})"
            )
        for stream in struct.streams:
            length = f"{struct.port}{arrow}{stream.length.access[1:]}"
            action = "write" if struct.output else "read"
            lines.append(
                f"    //   {stream.argument}: {action} {length} elements of {stream.element} "
                f"({stream.path}: {stream.ros_type})"
            )
            lines += [
                f"    //     .{f.access[1:]}: {f.ros_type} ({stream.path}.{f.path})"
                for f in stream.fields
            ]
    lines += ["}", ""]
    return "\n".join(lines)


def _declaration(top: str, structs: tuple[MessageStruct, ...], end: str) -> list[str]:
    arguments = [a for struct in structs for a in struct.arguments()]
    return [f"void {top}(", *(f"    {a}," for a in arguments[:-1]), f"    {arguments[-1]}){end}"]


def _definitions(struct: MessageStruct) -> list[str]:
    """C++ definitions of a port's element structs, nested structs and struct, innermost first."""
    lines: list[str] = []
    for stream in struct.streams:
        if stream.fields:
            lines += _struct(stream.argument, _tree(stream.fields))
    return lines + _struct(struct.port, _tree(struct.fields))


def _tree(fields: tuple[CField, ...]) -> dict[str | int, Any]:
    """Nest fields by member: dicts for structs, dicts keyed by int for arrays."""
    root: dict[str | int, Any] = {}
    for field in fields:
        node = root
        for step in field.member[:-1]:
            node = node.setdefault(step, {})
        node[field.member[-1]] = field
    return root


def _struct(name: str, node: dict[str | int, Any]) -> list[str]:
    lines: list[str] = []
    body = []
    for member, child in node.items():
        dimensions = ""
        while isinstance(child, dict) and child and all(isinstance(k, int) for k in child):
            dimensions += f"[{len(child)}]"
            child = child[0]
        if isinstance(child, CField):
            body.append(f"    {child.ctype} {member}{dimensions};  // {child.ros_type}")
        else:
            nested = f"{name}_{member}"
            lines += _struct(nested, child)
            body.append(f"    {nested}_t {member}{dimensions};")
    return [*lines, f"struct {name}_t {{", *body, "};", ""]
