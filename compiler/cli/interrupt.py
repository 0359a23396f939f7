"""Ctrl-C: stop every process rfc started (GHDL and whatever it runs), then exit quietly.

A simulator is started by cocotb's runner, which kills only its direct child when interrupted;
a child of that child, or a process started outside such a call, would outlive rfc. On SIGINT
rfc finds every descendant in ``/proc`` (Linux), kills it, and goes on as Python would
(KeyboardInterrupt, which the command line turns into exit status 130 without a traceback).
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from pathlib import Path
from types import FrameType

#: The exit status of a process ended by SIGINT, as shells report it.
INTERRUPTED_STATUS = 130


def descendants(pid: int | None = None) -> list[int]:
    """Every live descendant of `pid` (default: this process), parents before children."""
    root = os.getpid() if pid is None else pid
    children: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        with contextlib.suppress(OSError, ValueError, IndexError):
            # the command name in parentheses may hold spaces: the fields after it are fixed
            fields = stat.read_text().rsplit(")", 1)[1].split()
            children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    found: list[int] = []
    pending = [root]
    while pending:
        for child in children.get(pending.pop(), []):
            found.append(child)
            pending.append(child)
    return found


def stop_descendants() -> None:
    """Kill every descendant of this process (SIGKILL: a simulator may ignore SIGINT)."""
    for pid in descendants():
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)


def on_interrupt(signum: int, frame: FrameType | None) -> None:
    """SIGINT handler: stop every descendant, say so, and interrupt rfc itself."""
    stop_descendants()
    print("interrupted: stopped rfc and every process it started", file=sys.stderr)
    raise KeyboardInterrupt
