"""Run the real `rfc` command line in a subprocess, as users and external checks do."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path


def run_rfc(*args: str | Path, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "rfc", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        check=False,
    )
