"""The `rfc` command line: one typer app, one module per command group.

Exit status: 0 success, 1 an error in the user's input (printed as one message, no traceback),
2 bad usage (typer's own handling).
"""

from __future__ import annotations

import signal
import sys

import typer
from rich.console import Console

from rfc import __version__
from rfc.cli.build import build_app
from rfc.cli.dse import dse_app
from rfc.cli.interrupt import on_interrupt
from rfc.cli.msg import msg_app
from rfc.cli.sched import sched_app
from rfc.cli.sim import sim_app
from rfc.cli.stub import stub_app
from rfc.cli.wizard import wizard_app
from rfc.errors import RfcError

app = typer.Typer(
    name="rfc",
    help="Generate FPGA hardware/software architectures for ROS 1 and ROS 2.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)
app.add_typer(msg_app, name="msg")
app.add_typer(build_app)
app.add_typer(sim_app)
app.add_typer(sched_app, name="sched")
app.add_typer(dse_app)
app.add_typer(stub_app)
app.add_typer(wizard_app)


def _version(value: bool) -> None:
    if value:
        print(f"rfc {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Generate FPGA hardware/software architectures for ROS 1 and ROS 2."""


def main() -> None:
    """Run the command line; user errors become one message on stderr and exit status 1."""
    previous = signal.signal(signal.SIGINT, on_interrupt)  # typer exits 130, no traceback
    try:
        app()
    except RfcError as exc:
        console = Console(stderr=True, highlight=False, soft_wrap=True)
        console.print(f"[bold red]error:[/] {_escape(str(exc))}")
        sys.exit(1)
    finally:
        signal.signal(signal.SIGINT, previous)


def _escape(text: str) -> str:
    return text.replace("[", r"\[")
