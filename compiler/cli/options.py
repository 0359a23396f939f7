"""Command-line options several `rfc` commands share, declared once so that they read the same."""

from __future__ import annotations

from typing import Annotated

import typer

#: ``--json``: print the command's result as one JSON document instead of tables.
JsonOption = Annotated[bool, typer.Option("--json", help="Print one JSON document.")]
