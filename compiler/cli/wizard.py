"""`rfc wizard [-o FILE] [--answers FILE]`: build a spec by answering questions."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console

from rfc.errors import RfcError

wizard_app = typer.Typer()


@wizard_app.command("wizard")
def wizard(
    output: Annotated[
        Path,
        typer.Option(
            "--output",
            "-o",
            metavar="FILE",
            help="The spec to write: .yaml (Listing 1 form) or .py (Python form).",
        ),
    ] = Path("project.yaml"),
    answers: Annotated[
        Path | None,
        typer.Option(
            "--answers",
            metavar="FILE",
            help="Replay answers from FILE, one per line (an empty line takes the default).",
        ),
    ] = None,
) -> None:
    """Build a spec step by step; Enter at every prompt gives a valid starter system."""
    from rfc.wizard.model import SystemAnswers
    from rfc.wizard.prompts import Prompter
    from rfc.wizard.session import Session
    from rfc.wizard.write import check_draft, write_system

    if output.exists():
        raise RfcError(
            f"'{output}' already exists; the wizard writes a new spec",
            hint="choose another file with -o, or remove it",
        )
    if not output.parent.is_dir():
        raise RfcError(
            f"the folder of '{output}' does not exist",
            hint="create it first, or write the spec elsewhere with -o",
        )
    console = Console(highlight=False, soft_wrap=True)
    prompter = (
        Prompter.at_terminal(console) if answers is None else Prompter.from_file(answers, console)
    )
    base = output.parent

    status = Console(stderr=True, highlight=False)

    def recommend(draft: SystemAnswers) -> tuple[str, str]:
        with status.status("simulating the schedulers with rfc dse", spinner="dots"):
            design = check_draft(draft, output)
        assert design.infrastructure is not None
        scheduler = design.infrastructure.scheduler
        return scheduler.algorithm, scheduler.reason.removeprefix("rfc dse: ")

    system = Session(prompter, base).run(recommend)
    with status.status("checking the spec as rfc check does", spinner="dots"):
        written = write_system(system, output)
    for stub in written.stubs:
        console.print(f"wrote skeleton {stub}")
    console.print(f"wrote {written.spec}; rfc check: ok")
    console.print(
        f"next: rfc build {written.spec}  (then rfc sim {written.spec} --bag IN --out OUT)"
    )
