"""Run the real `rfc` command line in a subprocess, as users and external checks do."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Mapping
from pathlib import Path


def run_rfc(
    *args: str | Path, cwd: Path | None = None, env: Mapping[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    """Run ``rfc ARGS``; `env` adds variables to the environment."""
    return subprocess.run(
        [sys.executable, "-m", "rfc", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        env={**os.environ, **env} if env else None,
        check=False,
    )
