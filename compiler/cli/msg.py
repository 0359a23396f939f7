"""`rfc msg ...`: inspect message layouts and run a type's converters over a bag."""

from __future__ import annotations

import json
import sys
from functools import partial
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.table import Table

from rfc.cli.notes import note_skipped, note_skipped_topics
from rfc.cli.options import JsonOption, Simulator
from rfc.errors import RfcError
from rfc.files.directory import kept_in
from rfc.lib.converters.loopback_run import LoopbackReport, loopback
from rfc.messages.layout import Layout, LayoutField, flatten
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import select

msg_app = typer.Typer(
    help="Inspect ROS message layouts and test their hardware converters.", no_args_is_help=True
)

MiddlewareOption = Annotated[
    Middleware, typer.Option("--middleware", "-m", help="Wire format: ROS 1 or ROS 2 (CDR).")
]
DistroOption = Annotated[
    str | None,
    typer.Option(help="Type store to use: noetic (ROS 1), humble (ROS 2 default), jazzy, ..."),
]
MsgPathOption = Annotated[
    list[Path] | None,
    typer.Option(
        "--msg-path", help="Directory of your own <package>/msg/*.msg or *.idl (repeatable)."
    ),
]
BagTypesOption = Annotated[
    list[Path] | None,
    typer.Option("--bag", help="Bag whose embedded message definitions to use (repeatable)."),
]


@msg_app.command("show")
def show(
    type_name: Annotated[str, typer.Argument(help="Message type, e.g. sensor_msgs/Image.")],
    middleware: MiddlewareOption = Middleware.ROS2,
    distro: DistroOption = None,
    msg_path: MsgPathOption = None,
    bag: BagTypesOption = None,
    include: Annotated[
        list[str] | None, typer.Option(help="Select only these field paths (wildcards: *).")
    ] = None,
    exclude: Annotated[list[str] | None, typer.Option(help="Drop these field paths.")] = None,
    as_json: JsonOption = False,
) -> None:
    """Show the flattened layout of a message: leaf fields, widths, byte offsets."""
    for path in bag or ():
        note_skipped_topics(path)
    types = message_types(
        middleware,
        distro,
        tuple(str(p) for p in msg_path or ()),
        tuple(str(p) for p in bag or ()),
    )
    layout = select(flatten(types, type_name), include or (), exclude or ())
    if as_json:
        print(json.dumps(layout_json(layout, types.distro), indent=2))
    else:
        Console(highlight=False, width=None if sys.stdout.isatty() else 200).print(
            layout_table(layout, types.distro)
        )


def layout_json(layout: Layout, distro: str) -> dict[str, Any]:
    """A layout's JSON (docs/architecture.md), plus `align`, `kind`, `bound` and `element`."""
    return {
        "type": layout.display_name,
        "middleware": layout.middleware.value,
        "distro": distro,
        "fixed_size": layout.fixed_size,
        "fields": [_field_json(field) for field in layout.fields],
    }


def _field_json(field: LayoutField) -> dict[str, Any]:
    entry: dict[str, Any] = {
        "path": field.path,
        "type": field.ros_type,
        "bits": field.bits,
        "offset": field.offset,
        "selected": field.selected,
        "align": field.align,
        "kind": field.kind.value,
        "bound": field.bound,
    }
    if field.element is not None:
        entry["element"] = [_field_json(item) for item in field.element.fields]
    return entry


def layout_table(layout: Layout, distro: str) -> Table:
    """A readable table of the layout; elements of message sequences are indented below."""
    size = f"{layout.fixed_size} bytes" if layout.fixed_size is not None else "variable size"
    table = Table(
        title=f"{layout.display_name}  ({layout.middleware.label} {distro}, {size})",
        title_justify="left",
    )
    for heading, justify in (
        ("path", "left"),
        ("type", "left"),
        ("bits", "right"),
        ("offset", "right"),
        ("align", "right"),
        ("selected", "center"),
    ):
        table.add_column(heading, justify=justify)  # type: ignore[arg-type]
    _add_rows(table, layout, "")
    return table


def _add_rows(table: Table, layout: Layout, prefix: str) -> None:
    for field in layout.fields:
        bound = f" (≤{field.bound})" if field.bound else ""
        table.add_row(
            prefix + field.path,
            field.ros_type + bound,
            "" if field.bits is None else str(field.bits),
            "dynamic" if field.offset is None else str(field.offset),
            str(field.align),
            "yes" if field.selected else "-",
            style=None if field.selected else "dim",
        )
        if field.element is not None:
            _add_rows(table, field.element, f"{prefix}{field.path}[].")


def _bus_width(value: int) -> int:
    if value not in (8, 32, 64):
        raise typer.BadParameter(f"{value} is not a bus width; expected 8, 32 or 64")
    return value


@msg_app.command("loopback")
def loopback_command(
    type_name: Annotated[str, typer.Argument(help="Message type, e.g. nav_msgs/msg/Odometry.")],
    bag: Annotated[
        Path, typer.Option("--bag", help="ROS 1 .bag or ROS 2 .mcap/.db3 holding the messages.")
    ],
    topic: Annotated[str | None, typer.Option(help="Only the messages of this topic.")] = None,
    middleware: Annotated[
        Middleware | None,
        typer.Option(
            "--middleware", "-m", help="The bag's wire format (checked; default: the bag's)."
        ),
    ] = None,
    width: Annotated[
        int, typer.Option(help="AXI-Stream bus width in bits: 8, 32 or 64.", callback=_bus_width)
    ] = 64,
    count: Annotated[
        int | None, typer.Option(min=1, help="Only the first COUNT messages of the type.")
    ] = None,
    keep: Annotated[
        Path | None, typer.Option(help="Keep the generated VHDL and simulation files here.")
    ] = None,
    msg_path: MsgPathOption = None,
    include: Annotated[
        list[str] | None,
        typer.Option(help="Only these fields pass the converters (wildcards: *)."),
    ] = None,
    exclude: Annotated[
        list[str] | None,
        typer.Option(help="These fields do not; they come out at their defaults."),
    ] = None,
    simulator: Annotated[
        Simulator,
        typer.Option(
            "--simulator",
            help="GHDL (the VHDL) or Verilator (the Verilog, compiled once per converter pair "
            "and bus width, then cached).",
        ),
    ] = Simulator.GHDL,
    netlist: Annotated[
        bool,
        typer.Option(
            "--netlist",
            help="Simulate GHDL's synthesized netlist of the converters (in GHDL) instead of "
            "their VHDL: what synthesis makes of them.",
        ),
    ] = False,
    as_json: JsonOption = False,
) -> None:
    """Round-trip a bag's messages through the generated subscriber and publisher.

    Exit status 1 when any message does not come out as rosbags serializes it (with the
    fields left out by --include/--exclude at their defaults).
    """
    if netlist and simulator is not Simulator.GHDL:
        raise typer.BadParameter("--netlist simulates VHDL netlists: use --simulator ghdl")
    if not bag.exists():
        raise RfcError(f"bag '{bag}' does not exist", hint="give the path of a .bag, .mcap or .db3")
    run = partial(
        loopback,
        type_name,
        bag,
        topic=topic,
        middleware=middleware,
        width=width,
        count=count,
        msg_paths=tuple(msg_path or ()),
        include=tuple(include or ()),
        exclude=tuple(exclude or ()),
        simulator=simulator.value,
        netlist=netlist,
    )
    if keep is None:
        report = run()
    else:
        with kept_in(keep, "rfc msg loopback") as scratch:
            report = run(workdir=scratch)
    note_skipped(bag, report.skipped)
    if as_json:
        print(json.dumps(report.as_json(), indent=2))
    else:
        Console(highlight=False).print(loopback_table(report))
    if not report.equal:
        raise typer.Exit(1)


def loopback_table(report: LoopbackReport) -> Table:
    """A summary of a loopback run: messages, mismatches and the converters' cycle counts."""
    results = report.results
    table = Table(
        title=f"{report.type_name} loopback ({report.middleware.label}, {report.width}-bit bus)",
        title_justify="left",
    )
    table.add_column("measure")
    table.add_column("value", justify="right")
    mismatches = [str(r.index) for r in results if not r.equal]
    table.add_row("messages", str(len(results)))
    table.add_row("byte-exact", "all" if not mismatches else f"{len(results) - len(mismatches)}")
    if mismatches:
        table.add_row("differ (indices)", ", ".join(mismatches[:20]), style="red")
    for label, cycles in (
        (
            "subscriber cycles (first beat in -> fields valid)",
            [r.subscriber_cycles for r in results],
        ),
        ("publisher cycles (fields given -> last beat out)", [r.publisher_cycles for r in results]),
    ):
        table.add_row(label, f"{min(cycles)} .. {max(cycles)}")
    return table
