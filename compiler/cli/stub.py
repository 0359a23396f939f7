"""`rfc stub SPEC ACCELERATOR`: print a typed skeleton of one accelerator of a spec."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rfc.lower.stubs import StubLanguage

stub_app = typer.Typer()


@stub_app.command("stub")
def stub(
    spec: Annotated[
        Path, typer.Argument(metavar="SPEC", help="The system specification (.yaml or .py).")
    ],
    accelerator: Annotated[
        str,
        typer.Argument(metavar="ACCELERATOR", help="An accelerator type, or a block of one."),
    ],
    language: Annotated[
        StubLanguage,
        typer.Option("--lang", "-l", help="The skeleton's language.", case_sensitive=False),
    ] = StubLanguage.MYHDL,
) -> None:
    """Print a ready-to-fill skeleton of one accelerator, every port of its messages typed.

    The accelerator's source file need not exist yet: write the skeleton into it.
    """
    from rfc.driver import compile_spec
    from rfc.lower.stubs import accelerator_stub
    from rfc.spec.common import sources_may_be_missing

    with sources_may_be_missing():
        design = compile_spec(str(spec))
    print(accelerator_stub(design, accelerator, language), end="")
