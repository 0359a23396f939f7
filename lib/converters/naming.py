"""Port names from dotted field paths, valid in VHDL and Verilog alike.

``header.stamp.sec`` becomes ``header_stamp_sec`` and ``pose.covariance[35]`` becomes
``pose_covariance_35``. A name that is a VHDL, Verilog or Python keyword (``range``, ``type``,
``from`` ...; MyHDL names ports after Python parameters) gets the suffix ``_field``. Names that
still cannot be HDL identifiers, or that two fields share, are refused by
`rfc.lib.converters.plan` with an error naming the fields.
"""

from __future__ import annotations

import keyword
import re

#: Appended to a port name that would be an HDL keyword.
KEYWORD_SUFFIX = "_field"

_VHDL_KEYWORDS = frozenset(
    """abs access after alias all and architecture array assert assume attribute begin block body
    buffer bus case component configuration constant context cover default disconnect downto
    else elsif end entity exit fairness file for force function generate generic group guarded
    if impure in inertial inout is label library linkage literal loop map mod nand new next nor
    not null of on open or others out package parameter port postponed procedure process
    property protected pure range record register reject release rem report restrict return rol
    ror select sequence severity shared signal sla sll sra srl strong subtype then to transport
    type unaffected units until use variable vmode vprop vunit wait when while with xnor
    xor""".split()  # noqa: SIM905
)
_VERILOG_KEYWORDS = frozenset(
    """always and assign automatic begin buf bufif0 bufif1 case casex casez cell cmos config
    deassign default defparam design disable edge else end endcase endconfig endfunction
    endgenerate endmodule endprimitive endspecify endtable endtask event for force forever fork
    function generate genvar highz0 highz1 if ifnone incdir include initial inout input
    instance integer join large liblist library localparam macromodule medium module nand
    negedge nmos nor noshowcancelled not notif0 notif1 or output parameter pmos posedge
    primitive pull0 pull1 pulldown pullup pulsestyle_onevent pulsestyle_ondetect rcmos real
    realtime reg release repeat rnmos rpmos rtran rtranif0 rtranif1 scalared showcancelled
    signed small specify specparam strong0 strong1 supply0 supply1 table task time tran tranif0
    tranif1 tri tri0 tri1 triand trior trireg unsigned use uwire vectored wait wand weak0 weak1
    while wire wor xnor xor""".split()  # noqa: SIM905
)
_IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9]*(_[A-Za-z0-9]+)*")


def port_name(steps: tuple[str | int, ...], prefix: str = "") -> str:
    """Join path steps (names and fixed-array indices) with underscores behind `prefix`."""
    return prefix + "_".join(str(step) for step in steps)


def safe_name(name: str) -> str:
    """Return `name`, or `name` + `KEYWORD_SUFFIX` when it is a VHDL, Verilog or Python keyword."""
    if name.lower() in _VHDL_KEYWORDS or name in _VERILOG_KEYWORDS or keyword.iskeyword(name):
        return name + KEYWORD_SUFFIX
    return name


def is_identifier(name: str) -> bool:
    """Whether `name` is a basic VHDL identifier (hence also a Verilog one).

    VHDL forbids a leading digit or underscore, doubled underscores and a trailing underscore.
    """
    return _IDENTIFIER.fullmatch(name) is not None
