"""Telling text from binary files, so a binary spec or source gets a plain "not a …" message."""

from __future__ import annotations

from pathlib import Path


def binary_reason(path: Path) -> str | None:
    """Why `path` is not UTF-8 text (NUL bytes, or the first byte that is not UTF-8), or None.

    Raises:
        OSError: The file cannot be read.
    """
    data = path.read_bytes()
    if b"\0" in data:
        return "it holds NUL bytes"
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        return f"byte {exc.start} is not UTF-8"
    return None
