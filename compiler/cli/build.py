"""`rfc check SPEC` and `rfc build SPEC`: from a spec to the holistic model and artifacts."""

from __future__ import annotations

import sys
import warnings
from contextlib import AbstractContextManager, nullcontext
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console

from rfc.ir.model import BlockKind, Design

build_app = typer.Typer()

SpecArgument = Annotated[
    Path,
    typer.Argument(metavar="SPEC", help="The system specification: a .yaml file or a .py file."),
]


@build_app.command("check")
def check(spec: SpecArgument) -> None:
    """Validate a spec: run the whole pipeline and report the first error, if any."""
    from rfc.driver import compile_spec
    from rfc.passes.check_timing import BlockTimingWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", BlockTimingWarning)
        design = compile_spec(str(spec))
    _show(caught, (BlockTimingWarning,))
    print(f"ok: {spec}: {_summary(design)}")


@build_app.command("build")
def build(
    spec: SpecArgument,
    output: Annotated[
        Path,
        typer.Option(
            "--output", "-o", metavar="DIR", help="Output directory (replaced as a whole)."
        ),
    ] = Path("build"),
    emit_ir: Annotated[
        bool, typer.Option("--emit-ir", help="Write the holistic model to DIR/model.yaml.")
    ] = False,
    estimate: Annotated[
        bool,
        typer.Option(
            "--estimate",
            help="Estimate the logic's LUT/FF/DSP and Fmax with Yosys (xc7) for report.md.",
        ),
    ] = False,
    no_hardware: Annotated[
        bool,
        typer.Option(
            "--no-hardware",
            help="Skip the logic and its Vivado/HLS scripts: model, software and report only.",
        ),
    ] = False,
    dump_ir_after: Annotated[
        list[str] | None,
        typer.Option(
            "--dump-ir-after",
            metavar="PASS",
            help="Print the IR after this pass (repeatable): parse, resolve-types, "
            "check-connections, expand-selections, flatten-messages, derive-infrastructure, "
            "check-hardware, check-timing, resolve-scheduler.",
        ),
    ] = None,
) -> None:
    """Build every artifact of a spec into DIR, with report.md; nothing is written on error."""
    from rfc.driver import compile_spec
    from rfc.ir.text import format_ir
    from rfc.passes.check_timing import BlockTimingWarning
    from rfc.passes.pipeline import BUILD_PIPELINE, SOFTWARE_BUILD_PIPELINE, pass_names

    wanted = list(dict.fromkeys(dump_ir_after or ()))
    for name in wanted:
        if name not in pass_names(BUILD_PIPELINE):
            raise typer.BadParameter(
                f"'{name}' is not a pass; choose from {', '.join(pass_names(BUILD_PIPELINE))}",
                param_hint="--dump-ir-after",
            )

    def dump(name: str, design: Design) -> None:
        if name in wanted:
            sys.stdout.write(f"# IR after {name}\n{format_ir(design)}")

    pipeline = SOFTWARE_BUILD_PIPELINE if no_hardware else BUILD_PIPELINE
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", BlockTimingWarning)
        design = compile_spec(str(spec), after=dump, pipeline=pipeline)
    # the lowering (MyHDL and every hardware block: about a second) only for a valid spec, so
    # that a spec's error comes as fast as from `rfc check`
    from rfc.lower import lower
    from rfc.lower.artifacts import BuildOptions
    from rfc.lower.system.conversion_cache import conversion_key, conversions_cached
    from rfc.lower.system.estimate import TimingWarning
    from rfc.lower.writer import write_artifacts

    options = BuildOptions(emit_ir=emit_ir, estimate=estimate, hardware=not no_hardware)
    with (
        _working("estimating the logic with Yosys" if estimate else None),
        conversions_cached(conversion_key(spec, design, options)),
        warnings.catch_warnings(record=True) as lowering,
    ):
        warnings.simplefilter("always", TimingWarning)
        artifacts = lower(design, options, spec.read_text(encoding="utf-8"))
    _show([*caught, *lowering], (TimingWarning, BlockTimingWarning))
    write_artifacts(artifacts, output, str(output), inputs=_inputs(spec, design))
    names = ", ".join(a.path for a in artifacts)
    print(f"built {design.project.name} into {output}: {names}", file=sys.stderr)


def _show(caught: list[warnings.WarningMessage], ours: tuple[type[Warning], ...]) -> None:
    """Warnings of the `ours` kinds as ``warning: …`` lines on stderr, others as Python would."""
    for warning in caught:
        if issubclass(warning.category, ours):
            print(f"warning: {warning.message}", file=sys.stderr)
        else:  # not ours to word: as Python would have shown it
            warnings.showwarning(
                warning.message, warning.category, warning.filename, warning.lineno
            )


def _inputs(spec: Path, design: Design) -> tuple[Path, ...]:
    """Everything the build read: never overwritten nor deleted by the writer."""
    sources = (source for accelerator in design.accelerators for source in accelerator.sources)
    return (spec, *sources, *design.project.msg_paths)


def _working(what: str | None) -> AbstractContextManager[object]:
    """A spinner on stderr while a long step runs (at a terminal, when `what` names one)."""
    console = Console(stderr=True, highlight=False)
    if what is None or not console.is_terminal:
        return nullcontext()
    return console.status(what, spinner="dots")


def _summary(design: Design) -> str:
    counts = {kind: len(design.blocks_of(kind)) for kind in BlockKind}
    parts = [f"{n} {kind.value}{'s' if n != 1 else ''}" for kind, n in counts.items()]
    return (
        f"project {design.project.name}, {', '.join(parts)}, "
        f"{len(design.connections)} connection{'s' if len(design.connections) != 1 else ''}"
    )
