"""The manifest of an output directory: which files the last rfc run wrote there.

rfc deletes only what a manifest lists. The manifest is the marker file itself: a regular file
whose first line is `HEADER`, then one ``/``-separated relative path per line. Anything else
(a directory of that name, a symlink, other text) is not a manifest, and the directory is treated
as the user's.
"""

from __future__ import annotations

from pathlib import Path, PurePosixPath

#: The file that marks a directory as written by rfc and lists what rfc wrote there.
MARKER = ".rfc-build"

#: The first line of every manifest.
HEADER = "written by rfc; a rebuild deletes only the files listed below"


def manifest_text(paths: list[str]) -> str:
    """The contents of a marker listing `paths`."""
    return "\n".join([HEADER, *sorted(paths)]) + "\n"


def read_manifest(directory: Path) -> frozenset[str] | None:
    """The files rfc wrote in `directory`, or None when it holds no valid manifest."""
    marker = directory / MARKER
    if marker.is_symlink() or not marker.is_file():
        return None
    try:
        lines = marker.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    if not lines or lines[0] != HEADER:
        return None
    paths = lines[1:]
    if not all(_is_plain_relative(path) for path in paths):
        return None
    return frozenset(paths)


def files_under(directory: Path) -> list[str]:
    """Every file and symlink below `directory`, as ``/``-separated relative paths."""
    found = []
    for path in directory.rglob("*"):
        if path.is_symlink() or not path.is_dir():
            found.append(path.relative_to(directory).as_posix())
    return found


def _is_plain_relative(path: str) -> bool:
    pure = PurePosixPath(path)
    return bool(path) and not pure.is_absolute() and ".." not in pure.parts and path != MARKER
