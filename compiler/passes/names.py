"""Naming rules: names become VHDL identifiers and ROS topics, so they must be valid as both.

VHDL basic identifiers start with a letter, hold letters, digits and single underscores, do
not end with an underscore, are not reserved words, and are case-insensitive — so two blocks
whose names differ only in case would clash in the generated hardware. Names also become file
names, so they are at most `MAX_NAME_LENGTH` characters long.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from rfc.errors import RfcError, SourceLocation

_IDENTIFIER = re.compile(r"[A-Za-z](?:_?[A-Za-z0-9])*")
_TOPIC = re.compile(r"~?/?[A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*)*")
#: Reserved words of VHDL-2008 (IEEE 1076-2008 §15.10).
VHDL_RESERVED = frozenset(
    {
        "abs",
        "access",
        "after",
        "alias",
        "all",
        "and",
        "architecture",
        "array",
        "assert",
        "assume",
        "assume_guarantee",
        "attribute",
        "begin",
        "block",
        "body",
        "buffer",
        "bus",
        "case",
        "component",
        "configuration",
        "constant",
        "context",
        "cover",
        "default",
        "disconnect",
        "downto",
        "else",
        "elsif",
        "end",
        "entity",
        "exit",
        "fairness",
        "file",
        "for",
        "force",
        "function",
        "generate",
        "generic",
        "group",
        "guarded",
        "if",
        "impure",
        "in",
        "inertial",
        "inout",
        "is",
        "label",
        "library",
        "linkage",
        "literal",
        "loop",
        "map",
        "mod",
        "nand",
        "new",
        "next",
        "nor",
        "not",
        "null",
        "of",
        "on",
        "open",
        "or",
        "others",
        "out",
        "package",
        "parameter",
        "port",
        "postponed",
        "procedure",
        "process",
        "property",
        "protected",
        "pure",
        "range",
        "record",
        "register",
        "reject",
        "release",
        "rem",
        "report",
        "restrict",
        "restrict_guarantee",
        "return",
        "rol",
        "ror",
        "select",
        "sequence",
        "severity",
        "shared",
        "signal",
        "sla",
        "sll",
        "sra",
        "srl",
        "strong",
        "subtype",
        "then",
        "to",
        "transport",
        "type",
        "unaffected",
        "units",
        "until",
        "use",
        "variable",
        "vmode",
        "vprop",
        "vunit",
        "wait",
        "when",
        "while",
        "with",
        "xnor",
        "xor",
    }
)


#: The longest name a spec may give: generated file names add a suffix and must stay short.
MAX_NAME_LENGTH = 64


def snake_identifier(name: str) -> str:
    """A VHDL identifier made from a name: snake case, no doubled or trailing underscores."""
    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()
    cleaned = re.sub(r"_+", "_", re.sub(r"[^a-z0-9_]", "_", snake)).strip("_")
    return cleaned if cleaned[:1].isalpha() else f"x_{cleaned}"


def check_identifier(name: str, what: str, location: SourceLocation, where: str = "") -> None:
    """Raise unless `name` can be a VHDL identifier (`where` scopes it: `` of block 'X'``)."""
    if len(name) > MAX_NAME_LENGTH:
        raise RfcError(
            f"{what} '{name[:20]}...'{where} is {len(name):,} characters long; names are at "
            f"most {MAX_NAME_LENGTH}",
            location=location,
            hint="shorten it; it names generated files and hardware",
        )
    if not _IDENTIFIER.fullmatch(name):
        raise RfcError(
            f"{what} '{name}'{where} is not a valid name; it names generated hardware",
            location=location,
            hint="use a letter first, then letters, digits and single underscores, "
            "not ending in '_'",
        )
    if name.lower() in VHDL_RESERVED:
        raise RfcError(
            f"{what} '{name}'{where} is a reserved word of VHDL, where it names generated hardware",
            location=location,
            hint=f"rename it, e.g. '{name}_0'",
        )


def check_unique(named: Iterable[tuple[str, SourceLocation]], what: str, where: str = "") -> None:
    """Raise at the second of two equal names (or names differing only in case).

    Args:
        named: Names and where each was written.
        what: What the names name (``block``).
        where: The scope, for messages (`` in accelerator 'X'``).
    """
    seen: dict[str, tuple[str, SourceLocation]] = {}
    for name, location in named:
        key = name.lower()
        if key in seen:
            first, first_location = seen[key]
            if first == name:
                message = (
                    f"duplicate {what} name '{name}'{where} (first defined at {first_location})"
                )
            else:
                message = (
                    f"{what} name '{name}'{where} differs from '{first}' (at {first_location}) "
                    "only in case; the generated VHDL would not tell them apart"
                )
            raise RfcError(message, location=location)
        seen[key] = (name, location)


# Raises like `check_identifier`, for ROS graph names: slashes, no VHDL rules.
def check_topic(topic: str, owner: str, location: SourceLocation) -> None:
    """Raise unless `topic` is a valid ROS graph resource name."""
    if not _TOPIC.fullmatch(topic):
        raise RfcError(
            f"topic '{topic}' of {owner} is not a valid ROS name",
            location=location,
            hint="use letters, digits and underscores in '/'-separated parts that start with "
            "a letter, such as /imu/orientation",
        )
