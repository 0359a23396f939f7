"""Where rfc keeps what it computed once: ``$RFC_CACHE_DIR`` or ``~/.cache/rfc``.

Compiled simulators (Verilator models, GHDL programs) are kept as entries of a folder, one per
content of their sources. A build is made in a scratch folder beside its entry and published
whole (`publish_build`): its intermediates dropped (a Verilator model's precompiled headers
alone take 150 MB, its program 1 MB), then the folder pruned to the entries used last, so
that simulating many designs does not fill the disk.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

#: How many compiled simulators each cache folder keeps: the ones used last.
KEPT_BUILDS = 128
#: A scratch folder older than this was left by a build that died: it is removed.
ABANDONED_SECONDS = 24 * 3600
#: What a finished build no longer needs: precompiled headers, objects, archives, their
#: dependency lists (the program is linked).
INTERMEDIATES = ("*.gch", "*.o", "*.a", "*.d")


def cache_root() -> Path:
    """The folder of every rfc cache (each in a subfolder of its own)."""
    return Path(os.environ.get("RFC_CACHE_DIR") or Path.home() / ".cache" / "rfc")


@contextmanager
def scratch_build(entry: Path) -> Iterator[Path]:
    """A scratch folder beside `entry` to build into; removed on leaving unless published."""
    entry.parent.mkdir(parents=True, exist_ok=True)
    partial = Path(tempfile.mkdtemp(prefix=f"{entry.name}.", dir=entry.parent))
    try:
        yield partial
    finally:
        shutil.rmtree(partial, ignore_errors=True)


def publish_build(partial: Path, entry: Path, kept: int = KEPT_BUILDS) -> Path:
    """Make the finished build `partial` the cache entry `entry`; return the entry.

    The build's intermediates are dropped first. When another process published the same
    entry meanwhile, theirs is kept (the same content) and `partial` is left for
    `scratch_build` to remove. The folder then keeps its `kept` entries used last.
    """
    for pattern in INTERMEDIATES:
        for path in partial.glob(pattern):
            path.unlink()
    with contextlib.suppress(OSError):  # published meanwhile: the same build
        partial.rename(entry)
    prune(entry.parent, kept)
    return entry


def used(entry: Path) -> Path:
    """Mark `entry` as used now (pruning keeps the entries used last); return it."""
    with contextlib.suppress(OSError):  # not built yet, or pruned meanwhile
        os.utime(entry)
    return entry


def prune(folder: Path, kept: int) -> None:
    """Remove all but the `kept` entries of `folder` used last, and abandoned scratch folders.

    An entry is a folder whose name has no dot; a scratch folder (``entry.xyz``) is another
    build's until it is a day old.
    """
    now = time.time()
    entries: list[tuple[float, Path]] = []
    for path in folder.iterdir():
        with contextlib.suppress(OSError):  # removed meanwhile by another build
            mtime = path.stat().st_mtime
            if not path.is_dir():
                continue
            if "." not in path.name:
                entries.append((mtime, path))
            elif now - mtime > ABANDONED_SECONDS:
                shutil.rmtree(path, ignore_errors=True)
    entries.sort(reverse=True)
    for _, stale in entries[kept:]:
        shutil.rmtree(stale, ignore_errors=True)
