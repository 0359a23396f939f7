"""`rfc sched ...`: generate the hardware schedulers and measure them."""

from __future__ import annotations

import json
from functools import partial
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.table import Table

from rfc.cli.options import JsonOption
from rfc.cli.progress import run_counted
from rfc.errors import RfcError
from rfc.files.directory import replace_directory
from rfc.lib.schedulers.generate import (
    critical_path,
    entity_name,
    generate_hdl,
    grant_latency,
    synthesize,
)
from rfc.lib.schedulers.spec import (
    DEFAULT_TRANSFER,
    AnySchedulerSpec,
    SchedulerSpec,
    parse_scheduler,
)

sched_app = typer.Typer(help="Generate and measure the hardware schedulers.", no_args_is_help=True)


@sched_app.command("synth")
def synth(
    algorithm: Annotated[
        str,
        typer.Option(
            "--algorithm",
            "-a",
            help="LRU, NPFP, PFP, ROEDF, LOEDF or LST; or a composition such as "
            "'LRU(LOEDF,LST)' (children share the inputs evenly, or 'LRU(LOEDF:100,LST:28)').",
        ),
    ],
    n: Annotated[
        str,
        typer.Option(
            "--n",
            "-n",
            metavar="N",
            help="Number of inputs (accelerators); a list such as 8,16,32 sweeps them, one "
            "synthesis job each.",
        ),
    ],
    transfer: Annotated[
        int, typer.Option(help="Transfer time T of every input, in beats.")
    ] = DEFAULT_TRANSFER,
    deadline: Annotated[
        int | None, typer.Option(help="Relative deadline D in cycles (default T + 100).")
    ] = None,
    counter_bits: Annotated[
        int | None, typer.Option(help="Width of the deadline/slack counters.")
    ] = None,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="Also write the VHDL and Verilog here.")
    ] = None,
    no_cache: Annotated[
        bool, typer.Option("--no-cache", help="Synthesize even when a cached result exists.")
    ] = False,
    as_json: JsonOption = False,
    jobs: Annotated[
        int,
        typer.Option(
            min=1, help="With a list of N: synthesize on a local Dask cluster of this many workers."
        ),
    ] = 1,
    cluster: Annotated[
        str | None,
        typer.Option(
            metavar="ADDRESS", help="With a list of N: synthesize on this Dask scheduler."
        ),
    ] = None,
) -> None:
    """LUT/FF, Fmax and latency of one scheduler (GHDL synthesis + Yosys synth_xilinx, sta)."""
    sizes = _sizes(n)
    specs = [parse_scheduler(algorithm, size, transfer, deadline, counter_bits) for size in sizes]
    if len(specs) > 1:
        if output is not None:
            raise RfcError(
                "--output writes one scheduler's VHDL and Verilog; --n gives several",
                hint="run rfc sched synth once per N with --output",
            )
        _sweep(specs, not no_cache, as_json, jobs, cluster)
        return
    spec = specs[0]
    if output is not None:  # rfc's files only, all at once: the writer of rfc build
        fill = partial(generate_hdl, spec)
        replace_directory(output, str(output), fill, command="rfc sched synth")
    report = synth_report(spec, use_cache=not no_cache)
    if as_json:
        print(json.dumps(report, indent=2))
    else:
        Console(highlight=False).print(_table(report))


def _sizes(text: str) -> list[int]:
    try:
        sizes = sorted({int(part) for part in text.split(",") if part.strip()})
    except ValueError:
        raise typer.BadParameter(f"'{text}' is not an integer nor a list such as 8,16") from None
    if not sizes:
        raise typer.BadParameter("give at least one N")
    return sizes


def _sweep(
    specs: list[AnySchedulerSpec], use_cache: bool, as_json: bool, jobs: int, cluster: str | None
) -> None:
    """One synthesis job per N, here or on a Dask cluster; the reports in N's order."""
    reports, failures = run_counted(
        "synthesizing",
        partial(_report_job, use_cache=use_cache),
        specs,
        lambda spec: f"N={spec.n}",
        workers=jobs,
        address=cluster,
    )
    done = [report for report in reports if report is not None]
    if as_json:
        print(json.dumps(done, indent=2))
    else:
        Console(highlight=False).print(_sweep_table(done))
    if failures:
        raise RfcError(
            f"{len(failures)} of {len(specs)} syntheses failed ({'; '.join(map(str, failures))}); "
            "the others are above",
            hint="run the failed N alone to see the whole error",
        )


def _report_job(spec: AnySchedulerSpec, use_cache: bool) -> dict[str, Any]:
    return synth_report(spec, use_cache=use_cache)


def _sweep_table(reports: list[dict[str, Any]]) -> Table:
    title = f"{reports[0]['algorithm']} scheduler (xc7)" if reports else "no scheduler"
    table = Table(title=title)
    for heading in ("N", "LUTs", "flip-flops", "CARRY4", "grant latency"):
        table.add_column(heading, justify="right")
    for report in reports:
        table.add_row(
            *(str(report[k]) for k in ("n", "lut", "ff", "carry", "grant_latency_cycles"))
        )
    return table


def synth_report(spec: AnySchedulerSpec, *, use_cache: bool = True) -> dict[str, Any]:
    """The `rfc sched synth --json` document (docs/architecture.md; keys are only ever added)."""
    result = synthesize(spec, use_cache=use_cache)
    path = critical_path(spec, use_cache=use_cache)
    return {
        "algorithm": spec.algorithm.value if isinstance(spec, SchedulerSpec) else spec.name,
        "n": spec.n,
        "lut": result.resources.lut,
        "ff": result.resources.ff,
        "grant_latency_cycles": grant_latency(spec),
        "burst_latency_cycles": grant_latency(spec, requests=spec.n),
        "carry": result.resources.carry,
        "entity": entity_name(spec),
        "transfer": max(spec.transfer),
        "deadline": max(spec.deadline),
        "cached": result.cached,
        "fmax_mhz": None if path is None else round(path.fmax_mhz, 1),
        "critical_path": None if path is None else path.to_json(),
    }


def _table(report: dict[str, Any]) -> Table:
    table = Table(title=f"{report['algorithm']} scheduler, N = {report['n']} (xc7)")
    table.add_column("measure")
    table.add_column("value", justify="right")
    for key, label in (
        ("lut", "LUTs"),
        ("ff", "flip-flops"),
        ("carry", "CARRY4"),
        ("grant_latency_cycles", "grant latency (cycles, one request)"),
        ("burst_latency_cycles", "first grant after all N request (cycles)"),
    ):
        table.add_row(label, str(report[key]))
    path = report["critical_path"]
    if path is not None:
        table.add_row("cell delay of the critical path (ns)", f"{path['delay_ns']:.2f}")
        table.add_row("Fmax estimate (MHz, routing allowance included)", f"{path['fmax_mhz']:.0f}")
        table.add_row("critical path", f"{path['start']} → {path['end']}")
    return table
