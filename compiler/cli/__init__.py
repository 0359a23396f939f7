"""The `rfc` command line: one typer app, one module per command group.

Each command's module is imported only when that command runs, so that `rfc --help` and
`rfc check` do not pay for cocotb, MyHDL, numba or matplotlib (seconds of start-up otherwise).

Exit status: 0 success, 1 an error in the user's input (printed as one message, no traceback),
2 bad usage (typer's own handling).

Layer: the top one; it may import every package of rfc (docs/architecture.md).
"""

from __future__ import annotations

import signal
import sys
from dataclasses import dataclass
from difflib import get_close_matches
from importlib import import_module

import typer
from typer import _click  # typer's own click: its classes have no public name
from typer.core import TyperCommand, TyperGroup

from rfc import __version__
from rfc.cli.interrupt import on_interrupt
from rfc.errors import RfcError


@dataclass(frozen=True)
class LazyCommand:
    """Where a command lives, and the line `rfc --help` shows for it without importing it.

    Attributes:
        module: The module defining the command's typer app.
        app: The name of that typer app in the module.
        summary: The first paragraph of the command's help (a test holds it equal).
        group: Whether the app is a group of subcommands (`rfc msg show`) or holds the
            command itself among others (`rfc check` in the build module).
    """

    module: str
    app: str
    summary: str
    group: bool = False


#: Every command, in the order `rfc --help` lists them.
COMMANDS: dict[str, LazyCommand] = {
    "msg": LazyCommand(
        "rfc.cli.msg",
        "msg_app",
        "Inspect ROS message layouts and test their hardware converters.",
        group=True,
    ),
    "check": LazyCommand(
        "rfc.cli.build",
        "build_app",
        "Validate a spec: run the whole pipeline and report the first error, if any.",
    ),
    "build": LazyCommand(
        "rfc.cli.build",
        "build_app",
        "Build every artifact of a spec into DIR, with report.md; nothing is written on error.",
    ),
    "sim": LazyCommand(
        "rfc.cli.sim",
        "sim_app",
        "Replay a bag through the whole system and write each publisher's messages to OUT.",
    ),
    "sched": LazyCommand(
        "rfc.cli.sched", "sched_app", "Generate and measure the hardware schedulers.", group=True
    ),
    "dse": LazyCommand(
        "rfc.cli.dse",
        "dse_app",
        "Explore the schedulers (paper §7.2), or recommend one for the project SPEC.",
    ),
    "stub": LazyCommand(
        "rfc.cli.stub",
        "stub_app",
        "Print a ready-to-fill skeleton of one accelerator, every port of its messages typed.",
    ),
    "wizard": LazyCommand(
        "rfc.cli.wizard",
        "wizard_app",
        "Build a spec step by step; Enter at every prompt gives a valid starter system.",
    ),
}


def load_command(name: str) -> _click.Command:
    """Import the module of one command and return the click command typer builds from it."""
    entry = COMMANDS[name]
    group = typer.main.get_group(getattr(import_module(entry.module), entry.app))
    if entry.group:
        group.name = name
        return group
    return group.commands[name]


class LazyGroup(TyperGroup):
    """The root group: commands are imported on first use; the help lists their summaries."""

    _listing = False

    def list_commands(self, ctx: _click.Context) -> list[str]:
        """Every command's name, without importing any."""
        return list(COMMANDS)

    def get_command(self, ctx: _click.Context, cmd_name: str) -> _click.Command | None:
        """The command itself, or only its summary while the root help is written."""
        if cmd_name not in COMMANDS:
            return None
        if self._listing:
            return TyperCommand(cmd_name, help=COMMANDS[cmd_name].summary)
        if cmd_name not in self.commands:
            self.commands[cmd_name] = load_command(cmd_name)
        return self.commands[cmd_name]

    def resolve_command(
        self, ctx: _click.Context, args: list[str]
    ) -> tuple[str | None, _click.Command | None, list[str]]:
        """Find the command, suggesting near misses among all commands, loaded or not."""
        try:
            return self._click_resolve_command(ctx, args)
        except _click.exceptions.UsageError as error:
            matches = get_close_matches(args[0], list(COMMANDS)) if args else []
            if matches:
                suggestions = ", ".join(f"{m!r}" for m in matches)
                error.message = f"{error.message.rstrip('.')}. Did you mean {suggestions}?"
            raise

    def format_help(self, ctx: _click.Context, formatter: _click.HelpFormatter) -> None:
        """Write the root help from the summaries."""
        self._listing = True
        try:
            super().format_help(ctx, formatter)
        finally:
            self._listing = False


app = typer.Typer(
    name="rfc",
    cls=LazyGroup,
    help="Generate FPGA hardware/software architectures for ROS 1 and ROS 2.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)


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
        from rich.console import Console

        console = Console(stderr=True, highlight=False, soft_wrap=True)
        console.print(f"[bold red]error:[/] {_escape(str(exc))}")
        sys.exit(1)
    finally:
        signal.signal(signal.SIGINT, previous)


def _escape(text: str) -> str:
    return text.replace("[", r"\[")
