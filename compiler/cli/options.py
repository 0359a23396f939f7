"""Options and choices several `rfc` commands share, declared once so that they read the same."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

#: ``--json``: print the command's result as one JSON document instead of tables.
JsonOption = Annotated[bool, typer.Option("--json", help="Print one JSON document.")]


class Simulator(StrEnum):
    """Which HDL simulator runs generated logic (``--simulator``)."""

    GHDL = "ghdl"
    """The VHDL in GHDL (any logic)."""
    VERILATOR = "verilator"
    """The Verilog in Verilator (logic without VHDL accelerators); faster than GHDL."""
