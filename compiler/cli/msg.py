"""`rfc msg ...`: inspect message layouts."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.table import Table

from rfc.messages.layout import Layout, LayoutField, flatten
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import select

msg_app = typer.Typer(help="Inspect ROS message layouts.", no_args_is_help=True)

MiddlewareOption = Annotated[
    Middleware, typer.Option("--middleware", "-m", help="Wire format: ROS 1 or ROS 2 (CDR).")
]
DistroOption = Annotated[
    str | None,
    typer.Option(help="Type store to use: noetic (ROS 1), humble (ROS 2 default), jazzy, ..."),
]
MsgPathOption = Annotated[
    list[Path] | None,
    typer.Option("--msg-path", help="Directory of your own <package>/msg/*.msg (repeatable)."),
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
    as_json: Annotated[bool, typer.Option("--json", help="Print one JSON document.")] = False,
) -> None:
    """Show the flattened layout of a message: leaf fields, widths, byte offsets."""
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
    """The JSON form of a layout (DESIGN.md §9), with `align`, `kind`, `bound` and `element`."""
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
