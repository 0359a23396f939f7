"""The top function of an HLS accelerator, and how its arguments meet the message fields.

Convention (docs/accelerators.md): the top function returns void and takes, in order, one
argument per selected field of each input port (by value), then one pointer (or reference) per
field of each output port — the fields in the order `rfc msg show` lists them. Names are free,
so ``QuaternionToEuler(double x, ..., double *roll, ...)`` serves Quaternion → Point. With
``ap_ctrl_hs`` on the function, ``ap_none`` on inputs and ``ap_vld`` on outputs, Vitis HLS gives
the core the ports ``ap_clk ap_rst ap_start ap_done ap_idle ap_ready``, one port per input
named like the argument, and ``<name>``/``<name>_ap_vld`` per output; rfc's wrapper drives them.

Or, with rfc's generated header (`rfc.hls.c_types`), one struct per port (inputs by value,
outputs by pointer) followed by the port's ``hls::stream<T>`` references: such arguments are read
as `ArgumentKind.STRUCT` and `ArgumentKind.STREAM`.

Only the declaration of the top function is read, with a tokenizer for C declarators — not a C++
parser; anything it does not understand is an error that names the line.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from rfc.errors import RfcError, SourceLocation, did_you_mean

#: C/C++ scalar types and their widths in bits.
SCALAR_BITS = {
    "double": 64,
    "float": 32,
    "bool": 1,
    "char": 8,
    "signed char": 8,
    "unsigned char": 8,
    "short": 16,
    "unsigned short": 16,
    "int": 32,
    "unsigned": 32,
    "unsigned int": 32,
    "long long": 64,
    "unsigned long long": 64,
    **{f"{sign}int{bits}_t": bits for sign in ("", "u") for bits in (8, 16, 32, 64)},
}
_AP_INT = re.compile(r"^ap_u?int<\s*(\d+)\s*>$")
_COMMENTS = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)


class ArgumentKind(StrEnum):
    """What an argument of the top function is."""

    SCALAR = "scalar"
    STRUCT = "struct"
    STREAM = "stream"


_STREAM = re.compile(r"^hls::stream<(.+)>$")
_STRUCT = re.compile(r"^[A-Za-z_]\w*_t$")


@dataclass(frozen=True)
class HlsArgument:
    """One argument of the top function.

    Attributes:
        name: The argument's name (the core's port name).
        ctype: Its type without qualifiers, pointer or reference.
        bits: Width in bits (0 for structs and streams).
        output: Passed by pointer or reference: an output (streams: always).
        location: Where it is declared.
        kind: A scalar, a message struct or a stream.
        reference: Passed by reference (``&``) rather than by pointer or value.
    """

    name: str
    ctype: str
    bits: int
    output: bool
    location: SourceLocation
    kind: ArgumentKind = ArgumentKind.SCALAR
    reference: bool = False


def read_top_function(sources: list[Path], top: str) -> tuple[HlsArgument, ...]:
    """Find ``void top(...)`` in the sources and read its arguments.

    Raises:
        RfcError: No such function (with near names), or an argument rfc cannot map.
    """
    names: list[str] = []
    for path in sources:
        text = _COMMENTS.sub(lambda m: re.sub(r"[^\n]", " ", m.group()), path.read_text())
        for match in re.finditer(r"\bvoid\s+(\w+)\s*\(([^)]*)\)\s*\{", text):
            names.append(match.group(1))
            if match.group(1) == top:
                return tuple(_arguments(path, text, match.start(2), match.group(2)))
    raise RfcError(
        f"no HLS top function 'void {top}(...)' with a body in {', '.join(map(str, sources))}",
        hint=did_you_mean(top, names) or "name it with `top:` on the accelerator",
    )


def _arguments(path: Path, text: str, start: int, params: str) -> Iterator[HlsArgument]:
    offset = start
    for raw in params.split(","):
        location = _location(path, text, offset + len(raw) - len(raw.lstrip()))
        offset += len(raw) + 1
        declaration = " ".join(raw.replace("*", " * ").replace("&", " & ").split())
        if not declaration or declaration == "void":
            continue
        tokens = declaration.split(" ")
        name = tokens[-1]
        output = "*" in tokens or "&" in tokens
        ctype = " ".join(t for t in tokens[:-1] if t not in ("*", "&", "const", "volatile"))
        compact = ctype.replace(" ", "")
        if _STREAM.match(compact) or (_STRUCT.match(compact) and compact not in SCALAR_BITS):
            kind = ArgumentKind.STREAM if _STREAM.match(compact) else ArgumentKind.STRUCT
            yield HlsArgument(name, compact, 0, output, location, kind)
            continue
        bits = SCALAR_BITS.get(ctype)
        if bits is None and (ap := _AP_INT.match(ctype.replace(" ", ""))):
            bits = int(ap.group(1))
        if bits is None or not re.fullmatch(r"[A-Za-z_]\w*", name):
            raise RfcError(
                f"HLS argument '{declaration}' is neither a scalar, a message struct nor an "
                "hls::stream",
                location=location,
                hint="use double, float, (u)intN_t, bool or ap_(u)int<N> per field, or the "
                "message structs and hls::stream<T> of <accelerator>_messages.h "
                "(docs/accelerators.md)",
            )
        yield HlsArgument(name, ctype, bits, output, location, reference="&" in tokens)


def _location(path: Path, text: str, offset: int) -> SourceLocation:
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return SourceLocation(str(path), line, column)
