"""docs/architecture.md's command-line contract names every (visible) option of each command."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest
import typer

from rfc.cli import app

ARCHITECTURE = Path(__file__).parents[2] / "docs" / "architecture.md"


def _commands(group: Any, prefix: str = "rfc") -> dict[str, Any]:
    """Every leaf command under a Typer (click) group, by its full name."""
    found: dict[str, Any] = {}
    context = group.make_context(prefix, [], resilient_parsing=True)
    for name in group.list_commands(context):
        command = group.get_command(context, name)
        if hasattr(command, "list_commands"):
            found |= _commands(command, f"{prefix} {name}")
        else:
            found[f"{prefix} {name}"] = command
    return found


COMMANDS = _commands(typer.main.get_command(app))


def _documented_lines(command: str) -> str:
    block = ARCHITECTURE.read_text().split("## Command line", 1)[1].split("```")[1]
    return "\n".join(line for line in block.splitlines() if line.startswith(f"{command} "))


def test_every_command_is_documented():
    assert all(_documented_lines(command) for command in COMMANDS), [
        command for command in COMMANDS if not _documented_lines(command)
    ]


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_option_of_a_command_is_on_its_line(command):
    documented = set(re.findall(r"(?<![\w-])-{1,2}[a-z][a-z0-9-]*", _documented_lines(command)))
    for parameter in COMMANDS[command].params:
        if parameter.param_type_name != "option" or parameter.hidden or parameter.name == "help":
            continue
        names = [*parameter.opts, *parameter.secondary_opts]
        assert documented & set(names), f"{command}: none of {names} in docs/architecture.md"
