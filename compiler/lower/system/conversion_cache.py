"""A cache of the HDL rfc converts from MyHDL, so a build of an unchanged spec converts nothing.

Elaborating and converting the logic's blocks is most of a warm `rfc build --estimate` (the
quaternion core alone takes seconds). A build's *conversion key* is a hash of everything the
generated HDL depends on: the spec, the message files, the accelerators' sources, every Python
module the process loaded from outside the Python installation (the project's own modules,
wherever they lie), rfc's own files, the MyHDL and Python versions and the build's options.
Files count by name and content, not by folder, so a copy of a project elsewhere (a test's
temporary folder) converts the same. Within a build run under `conversions_cached`, each
block's files are kept under ``$RFC_CACHE_DIR/conversion`` by the key and the block's entity
name, and a later build with the same key copies them instead of converting: the same bytes.
The latencies a build measures in MyHDL's simulator are kept the same way
(`cached_measurement`). A file an accelerator reads while it elaborates (other than Python it
imports) is not in the key.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import sys
import sysconfig
import tempfile
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextvars import ContextVar
from functools import cache
from importlib import metadata
from pathlib import Path
from typing import Any

from rfc.ir.model import Design
from rfc.toolchain.cache import cache_root

#: Changes whenever what a cache entry holds changes, so old entries go unused.
_FORMAT = "rfc conversion cache, v1"
#: The key of the build running now, or None outside `conversions_cached` (nothing cached).
_BUILD_KEY: ContextVar[str | None] = ContextVar("rfc_conversion_key", default=None)
#: An entry's list of its files, in the order the conversion returned them; written last.
_LISTING = "files.json"
#: How many versions of rfc's files keep their entries (the versions used last).
KEPT_VERSIONS = 8


def conversion_key(spec: Path, design: Design, options: object) -> str:
    """The hash of everything a build's HDL depends on (the module docstring lists it)."""
    digest = hashlib.sha256()
    for part in (_FORMAT, rfc_digest(), _versions(), repr(options)):
        digest.update(part.encode() + b"\n")
    read = [spec, *design.project.msg_paths]
    read += [source for accelerator in design.accelerators for source in accelerator.sources]
    # by name and content, not folder: a copy of a project elsewhere converts the same
    contents = sorted((p.name, p.read_bytes() if p.is_file() else b"") for p in read)
    contents += sorted((p.name, p.read_bytes()) for p in project_modules())
    for name, content in contents:
        digest.update(f"{name} {len(content)}\n".encode() + content)
    return digest.hexdigest()


@contextlib.contextmanager
def conversions_cached(key: str) -> Iterator[None]:
    """Within this context, `converted` reuses the files of earlier builds with the same key.

    Entries are grouped by rfc's own files (`rfc_digest`); each build marks its group as
    used and drops all but the `KEPT_VERSIONS` groups used last, so developing rfc (a new
    group with every edit) does not grow the cache without bound.
    """
    _prune(_group())
    token = _BUILD_KEY.set(key)
    try:
        yield
    finally:
        _BUILD_KEY.reset(token)


def converted(name: str, directory: Path, convert: Callable[[], Sequence[Path]]) -> list[Path]:
    """The files of entity `name` in `directory`: copied from the cache, or `convert`'s.

    `convert` writes them into `directory` and returns them; outside `conversions_cached` it
    always runs. An entry is published whole (its folder renamed into place) or not at all.
    """
    key = _BUILD_KEY.get()
    if key is None:
        return list(convert())
    entry = _group() / hashlib.sha256(f"{key}\n{name}".encode()).hexdigest()
    listing = entry / _LISTING
    with contextlib.suppress(OSError):  # missing, or pruned by another build meanwhile
        names = json.loads(listing.read_text())
        directory.mkdir(parents=True, exist_ok=True)
        for file_name in names:
            shutil.copyfile(entry / file_name, directory / file_name)
        return [directory / file_name for file_name in names]
    files = list(convert())
    _publish(entry, files)
    return files


def cached_measurement(name: str, measure: Callable[[], Any]) -> Any:
    """`measure()`'s value, kept as JSON beside the converted files of the build's key.

    For figures a build measures by simulating the blocks it converts (the report's latencies:
    seconds of MyHDL elaboration for the quaternion core): they depend on what the key covers.
    The value always goes through JSON, so a cold build reports what a warm one reads back.
    `name` must not be an entity's: one with a space is none.
    """
    with tempfile.TemporaryDirectory(prefix="rfc-measured-") as scratch:
        folder = Path(scratch)

        def write() -> list[Path]:
            path = folder / "value.json"
            path.write_text(json.dumps(measure()))
            return [path]

        (path,) = converted(name, folder, write)
        return json.loads(path.read_text())


def _publish(entry: Path, files: Sequence[Path]) -> None:
    """Copy `files` into a new folder, then rename it to `entry`.

    Best effort: when another build published the same entry meanwhile, or pruned its group,
    the entry is left to them (the build has its files either way).
    """
    partial = None
    try:
        entry.parent.mkdir(parents=True, exist_ok=True)
        partial = Path(tempfile.mkdtemp(prefix=f"{entry.name}.", dir=entry.parent))
        for path in files:
            shutil.copyfile(path, partial / path.name)
        (partial / _LISTING).write_text(json.dumps([path.name for path in files]))
        partial.rename(entry)
    except OSError:
        if partial is not None:
            shutil.rmtree(partial, ignore_errors=True)


def _group() -> Path:
    """The folder of the entries made by this version of rfc's files."""
    return cache_root() / "conversion" / rfc_digest()[:24]


def _prune(group: Path) -> None:
    """Mark `group` as used now; delete the groups beyond the `KEPT_VERSIONS` used last."""
    try:
        group.mkdir(parents=True, exist_ok=True)
        os.utime(group)
        groups = sorted(group.parent.iterdir(), key=_used, reverse=True)
    except OSError:  # pruned by a concurrent build: this one publishes into it again
        return
    for stale in groups[KEPT_VERSIONS:]:
        shutil.rmtree(stale, ignore_errors=True)


def _used(group: Path) -> float:
    """When a build last used `group` (0 when it is gone meanwhile)."""
    try:
        return group.stat().st_mtime
    except OSError:
        return 0.0


@cache
def rfc_digest() -> str:
    """A hash of rfc's own files (the packages' folders, wherever rfc is installed)."""
    return source_digest(_rfc_folders())


def _rfc_folders() -> list[Path]:
    """The folders of rfc's packages (one each when installed in place, else nested)."""
    import rfc
    import rfc.lib

    return [Path(folder).resolve() for folder in (*rfc.__path__, *rfc.lib.__path__)]


def source_digest(folders: Iterable[Path]) -> str:
    """A hash of every file below `folders` (names and contents; compiled bytecode left out)."""
    digest = hashlib.sha256()
    for folder in folders:
        for path in sorted(folder.rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                digest.update(str(path.relative_to(folder)).encode() + b"\n")
                digest.update(path.read_bytes())
    return digest.hexdigest()


def project_modules() -> list[Path]:
    """The files of every loaded Python module outside the Python installation and rfc, sorted.

    The accelerators and what they import are loaded by the time a build converts (the
    check-timing pass elaborates them). rfc's own modules are left out (`rfc_digest` covers
    them), so the key does not depend on which of them the process loaded.
    """
    installed = {Path(p).resolve() for p in sysconfig.get_paths().values()}
    installed |= {Path(p).resolve() for p in (sys.prefix, sys.base_prefix, sys.exec_prefix)}
    installed |= set(_rfc_folders())
    files = set()
    for module in list(sys.modules.values()):
        name = getattr(module, "__file__", None)
        if not name:
            continue
        path = Path(name).resolve()
        # a module whose file is gone (a test's or a wizard's temporary spec) is read no more
        project = not any(path.is_relative_to(p) for p in installed)
        if path.suffix == ".py" and path.is_file() and project:
            files.add(path)
    return sorted(files)


def _versions() -> str:
    """The versions the conversion's output depends on besides rfc's: MyHDL's, Python's."""
    return f"myhdl {metadata.version('myhdl')}, python {sys.version_info[:2]}"
