"""Lowering: the holistic model becomes artifacts, written to the output directory at once.

A lowering is a function ``(design, options) -> artifacts`` (it may also yield
`ReportSection`s: figures for report.md). To add an artifact kind (VHDL,
tcl, the runtime's configuration...), write one such function in its own module and add it to
`LOWERINGS` (in `rfc.lower.lowerings`). `lower` runs them all in memory, then the report counts
their lines; only then does `rfc.lower.writer` put anything on disk, so an error leaves nothing
half-written.

`lower` and `LOWERINGS` are imported on first use, so that one module of the package
(`rfc.lower.writer`, say) does not import every generator of the logic.

Layer: below the driver; it may import `rfc.passes` and every layer under it, never the driver,
the wizard or the command line.
"""

from __future__ import annotations

from typing import Any


def __getattr__(name: str) -> Any:
    """Import the lowerings on first use of `lower` or `LOWERINGS`."""
    if name in ("LOWERINGS", "lower"):
        from rfc.lower import lowerings

        return getattr(lowerings, name)
    raise AttributeError(f"module 'rfc.lower' has no attribute '{name}'")
