"""`rfc dse [SPEC]`: the paper's scheduler evaluation, or a scheduler recommended for a project.

Without SPEC it sweeps the schedulers over the datasets (docs/dse.md), prints the metrics and
writes tables, an HTML report and (over more than one N, or with `--figures`) the paper's figures
into DIR;
`--verify-hdl` re-runs sampled points on the generated hardware in GHDL. With SPEC it ranks the
candidate schedulers for the project's publishers by the objective and prints the
recommendation with its reasons.
"""

from __future__ import annotations

import json
import sys
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.console import Console
from rich.table import Table

from rfc.cli.options import JsonOption
from rfc.cli.progress import counting_bar
from rfc.errors import RfcError

if TYPE_CHECKING:
    from rfc.dse.sweep import SweepResult

dse_app = typer.Typer()

#: Smallest and largest number of accelerators a sweep accepts.
MIN_N, MAX_N = 2, 1024

SpecArgument = Annotated[
    Path | None,
    typer.Argument(
        metavar="[SPEC]",
        help="A project spec: recommend its scheduler. Without it: the paper's sweep.",
    ),
]


def _sizes(text: str | None) -> tuple[int, ...]:
    from rfc.dse.datasets import SIZES

    if text is None:
        return SIZES
    try:
        sizes = tuple(sorted({int(part) for part in text.split(",") if part.strip()}))
    except ValueError:
        raise RfcError(
            f"--n '{text}' is not a comma-separated list of integers", hint="for example --n 8,16"
        ) from None
    if not sizes or min(sizes) < MIN_N or max(sizes) > MAX_N:
        raise RfcError(
            f"--n '{text}': each N must be between {MIN_N} and {MAX_N}",
            hint=f"the paper's sizes are {','.join(map(str, SIZES))}",
        )
    return sizes


def _sweep_only(options: dict[str, object]) -> None:
    """With SPEC, options that only shape the paper's sweep are a mistake, not silently ignored."""
    given = [name for name, value in options.items() if value not in (None, False)]
    if given:
        raise RfcError(
            f"{', '.join(given)} appl{'ies' if len(given) == 1 else 'y'} to the paper's sweep, "
            "not to a project's recommendation",
            hint="drop SPEC to run the sweep, or these options to rank the project's schedulers",
        )


@dse_app.command("dse")
def dse(
    spec: SpecArgument = None,
    n: Annotated[
        str | None,
        typer.Option("--n", metavar="LIST", help="Accelerator counts, e.g. 8,16 (default 2…256)."),
    ] = None,
    dataset: Annotated[
        str | None,
        typer.Option(help="Only this dataset: large, cc1, cc2, cc3 or cc4 (default: all five)."),
    ] = None,
    replicates: Annotated[
        int | None,
        typer.Option(min=2, help="Replicates per point (default: 200 large, 10 corner cases)."),
    ] = None,
    jobs: Annotated[
        int | None, typer.Option(min=1, help="Worker processes (default: one per core).")
    ] = None,
    cluster: Annotated[
        str | None,
        typer.Option(
            metavar="ADDRESS",
            help="Run the sweep's simulations on this Dask scheduler (tcp://host:8786; needs "
            "the cluster extra).",
        ),
    ] = None,
    output: Annotated[
        Path | None,
        typer.Option("--output", "-o", metavar="DIR", help="Where results go (sweep: dse/)."),
    ] = None,
    as_json: JsonOption = False,
    verify_hdl: Annotated[
        bool,
        typer.Option(
            "--verify-hdl",
            help="Re-run each algorithm's first replicate at the smallest N in GHDL; fail on "
            "any difference in the metrics.",
        ),
    ] = False,
    # Typer declares every option in the signature: rfc sim's options look alike, not the same.
    no_synth: Annotated[
        bool, typer.Option("--no-synth", help="Skip LUT/FF (Figure 6, Table 3).")
    ] = False,
    figures: Annotated[
        bool | None,
        typer.Option(
            "--figures/--no-figures",
            help="Draw Figures 6-14 and Table 3 (PNG, SVG) into DIR and report.html; by "
            "default when the sweep has more than one N (the figures plot against N).",
            show_default=False,
        ),
    ] = None,
    objective: Annotated[
        str | None,
        typer.Option(
            metavar="CRITERIA",
            help="Project ranking, best first: completed, missed, lateness, max_lateness, "
            "response, preemptions, utilization, lut, ff (default "
            "completed,missed,max_lateness,lut).",
        ),
    ] = None,
    seed: Annotated[int | None, typer.Option(help="Seed of the datasets (default 0).")] = None,
    horizon: Annotated[
        int | None,
        typer.Option(
            min=1,
            metavar="CYCLES",
            help="Cycles a project is simulated (default: ten periods of its slowest publisher).",
        ),
    ] = None,
) -> None:
    """Explore the schedulers (paper §7.2), or recommend one for the project SPEC."""
    from rfc.dse.engine import default_jobs

    workers = jobs or default_jobs()
    if spec is not None:
        _sweep_only(
            {"--n": n, "--dataset": dataset, "--replicates": replicates,
             "--verify-hdl": verify_hdl, "--no-synth": no_synth, "--seed": seed,
             "--cluster": cluster, "--figures": figures}
        )  # fmt: skip
        _project(spec, objective, output, as_json, horizon)
        return
    if horizon is not None:
        raise RfcError(
            "--horizon sets how long a project is simulated; give the project's SPEC",
            hint="the sweep's horizons are the datasets' (100 us large, 500 us corner cases)",
        )
    if objective is not None:
        raise RfcError(
            "--objective ranks a project's schedulers; give the project's SPEC",
            hint="rfc dse examples/sensor_hub/SensorHub.yaml --objective completed,lut",
        )
    _sweep(
        _sizes(n), dataset, replicates, workers, output or Path("dse"), as_json, verify_hdl,
        not no_synth, seed or 0, cluster, len(_sizes(n)) > 1 if figures is None else figures,
    )  # fmt: skip


def _sweep(
    sizes: tuple[int, ...],
    dataset: str | None,
    replicates: int | None,
    jobs: int,
    output: Path,
    as_json: bool,
    verify: bool,
    synthesis: bool,
    seed: int,
    cluster: str | None,
    figures: bool,
) -> None:
    from rfc.dse.datasets import DATASETS
    from rfc.dse.datasets import dataset as find_dataset
    from rfc.dse.output import write_sweep
    from rfc.dse.sweep import Plan, run_sweep
    from rfc.dse.tables import document

    names = (find_dataset(dataset).name,) if dataset else tuple(DATASETS)
    plan = Plan(datasets=names, sizes=sizes, replicates=replicates, seed=seed)
    _load_kernels()
    with counting_bar("{task.description}", percent=True) as progress:
        task = progress.add_task("simulating", total=1.0)
        result = run_sweep(
            plan,
            jobs,
            synthesis=False,
            advance=lambda share: progress.advance(task, share),
            cluster=cluster,
        )
        if synthesis:
            from rfc.dse.sweep import synthesized_resources

            progress.add_task("synthesizing (cached)", total=None)
            result = replace(result, resources=synthesized_resources(sizes, jobs))
        checks = []
        if verify:
            from rfc.dse.verify import verify_hdl

            progress.add_task("verifying in GHDL", total=None)
            checks = verify_hdl(result, jobs)
    write_sweep(result, checks, output, jobs, figures)
    report: dict[str, Any] = {**document(result), "output": str(output)}
    if verify:
        report["verify_hdl"] = [check.as_dict() for check in checks]
    if as_json:
        print(json.dumps(report, indent=1))
    else:
        _print_sweep(result, Console(highlight=False))
        written = "tables, figures and report.html" if figures else "tables and report.html"
        print(f"wrote {written} into {output}", file=sys.stderr)
    if result.failures:
        raise RfcError(
            f"{len(result.failures)} of the sweep's jobs failed on the cluster, the other "
            f"points are in {output}: {'; '.join(result.failures)}",
            hint="rerun the sweep to fill in the missing points",
        )
    failed = [check for check in checks if not check.equal]
    if failed:
        details = "; ".join(f"{c.scheduler} N={c.n}: {c.error or 'metrics differ'}" for c in failed)
        raise RfcError(
            f"--verify-hdl: the generated hardware disagrees with the DSE on {len(failed)} of "
            f"{len(checks)} points: {details}",
            hint=f"compare dse and ghdl values in {output}/verify.json",
        )
    if verify and not as_json:
        print(f"--verify-hdl: {len(checks)} points equal in GHDL", file=sys.stderr)


def _load_kernels() -> None:
    """Load the kernels before the sweep, compiling them first (saying so) if numba lacks them."""
    from rfc.dse.engine import load_kernels
    from rfc.dse.kernel import compiled

    if not compiled():
        print(
            "compiling the DSE kernels with numba (about 30 s, once: later runs load them from "
            "its cache)",
            file=sys.stderr,
        )
    load_kernels()


#: Columns of the printed sweep: metric and short heading.
_SHOWN = (
    ("completed", "completed"),
    ("granted", "granted"),
    ("preemptions", "preempt."),
    ("response", "response"),
    ("lateness", "lateness"),
    ("utilization", "U"),
)


def _print_sweep(result: SweepResult, console: Console) -> None:
    for name in result.plan.datasets:
        table = Table(title=f"dataset {name}: mean ±95 % CI over replicates (cycles)")
        table.add_column("scheduler")
        table.add_column("N", justify="right")
        for _, heading in _SHOWN:
            table.add_column(heading, justify="right")
        for point in (p for p in result.points if p.dataset == name):
            cells = []
            for metric, _ in _SHOWN:
                s = point.summary(metric)
                cells.append("n/a" if s.mean != s.mean else f"{s.mean:.3g} ±{s.ci95:.2g}")
            table.add_row(point.scheduler, str(point.n), *cells)
        console.print(table)


def _project(
    spec: Path, objective: str | None, output: Path | None, as_json: bool, horizon: int | None
) -> None:
    from rfc.driver import compile_spec
    from rfc.dse.objective import DEFAULT_OBJECTIVE, parse_objective
    from rfc.dse.output import recommendation_document, write_recommendation
    from rfc.dse.project import project_traffic, recommend
    from rfc.passes.pipeline import MODEL_PIPELINE

    criteria = parse_objective(objective or ",".join(DEFAULT_OBJECTIVE))
    # the publishers' traffic is the model's: accelerators still being written do not matter
    design = compile_spec(str(spec), pipeline=MODEL_PIPELINE)
    assert design.infrastructure is not None  # the model pipeline derives it
    traffic = project_traffic(design.project.name, design.infrastructure.scheduler.inputs, horizon)
    _load_kernels()
    with counting_bar("simulating candidates", hidden=as_json) as bar:
        task = bar.add_task("candidates", total=None)
        recommendation = recommend(
            traffic,
            criteria,
            progress=lambda done, total: bar.update(task, completed=done, total=total),
        )
    report = recommendation_document(design.project.name, recommendation)
    if output is not None:
        write_recommendation(report, output)
    if as_json:
        print(json.dumps(report, indent=1))
        return
    console = Console(highlight=False)
    console.print(
        f"[bold]{design.project.name}[/]: {traffic.n} publishers, {traffic.cycles} cycles "
        f"simulated ({min(traffic.messages)} to {max(traffic.messages)} messages each); "
        f"objective {', '.join(c.name for c in criteria)}"
    )
    table = Table()
    table.add_column("rank", justify="right")
    table.add_column("scheduler")
    for criterion in criteria:
        table.add_column(criterion.label, justify="right")
    for place, candidate in enumerate(recommendation.ranking, start=1):
        values = [criterion.describe(candidate.value(criterion)) for criterion in criteria]
        values = [
            "not synthesized" if v == "undefined" and c.resource else v
            for v, c in zip(values, criteria, strict=True)
        ]
        table.add_row(str(place), candidate.scheduler, *values)
    console.print(table)
    console.print(f"[bold]recommended: {recommendation.scheduler}[/]")
    for reason in recommendation.reasons:
        console.print(f"  - {reason}")
