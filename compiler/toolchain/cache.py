"""Where rfc keeps what it computed once: ``$RFC_CACHE_DIR`` or ``~/.cache/rfc``."""

from __future__ import annotations

import os
from pathlib import Path


def cache_root() -> Path:
    """The folder of every rfc cache (each in a subfolder of its own)."""
    return Path(os.environ.get("RFC_CACHE_DIR") or Path.home() / ".cache" / "rfc")
