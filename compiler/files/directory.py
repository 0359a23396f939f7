"""Writing an output directory all at once, or not at all.

Everything is written into a fresh staging directory beside the target, which then replaces
the target in one rename; an error or Ctrl-C on the way leaves the target as it was. rfc deletes
only the files its last run listed in the directory's manifest (`rfc.files.manifest`): any other
file in the directory, and every input (the spec, sources, message definitions) inside it, is
carried over into the new directory unchanged, and a generated file that would replace one of
them is an error. A non-empty directory without a manifest is never touched.
"""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path, PurePosixPath

from rfc.errors import RfcError
from rfc.files.manifest import MARKER, files_under, manifest_text, read_manifest

__all__ = ["MARKER", "kept_in", "replace_directory"]


def replace_directory(
    directory: Path,
    display: str,
    fill: Callable[[Path], object],
    command: str = "rfc build",
    inputs: Iterable[Path] = (),
) -> None:
    """Replace rfc's files in `directory` by those `fill` writes, or leave it untouched.

    Args:
        directory: The output directory.
        display: How to name it in messages.
        fill: Writes the files into the staging directory it is given (text or binary); what
            it returns is ignored.
        command: The command writing it, for messages.
        inputs: Files and directories the command read; never overwritten nor deleted.

    Raises:
        RfcError: The directory exists but was not written by rfc, cannot be written, or a
            file would replace an input or a file rfc did not write.
    """
    target = directory.resolve()
    if target.exists() and not target.is_dir():
        raise RfcError(f"output '{display}' exists and is not a directory")
    kept = _files_to_keep(target, display, command, inputs)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=target.parent))
        staging.chmod(0o755)  # mkdtemp makes it private; a build directory is not
    except OSError as exc:
        raise RfcError(f"cannot create output directory '{display}': {exc}") from None
    try:
        fill(staging)
        written = files_under(staging)
        _refuse_clashes(written, kept, display, command)
        for path in sorted(kept):
            _carry_over(target / path, staging / path)
        (staging / MARKER).write_text(manifest_text(written), encoding="utf-8")
        _swap(staging, target)
    except OSError as exc:
        raise RfcError(f"cannot write output directory '{display}': {exc}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


@contextmanager
def kept_in(directory: Path, command: str) -> Iterator[Path]:
    """A scratch directory whose files replace rfc's files in `directory` when the block ends.

    For commands that keep their working files on request (``--keep DIR``): `directory` is
    checked first, so a directory rfc would refuse is refused before any work; the files are
    kept even when the work fails, for its logs.

    Raises:
        RfcError: `directory` is a file, or a non-empty directory rfc did not write.
    """
    display = str(directory)
    target = directory.resolve()
    if target.exists() and not target.is_dir():
        raise RfcError(f"'{display}' exists and is not a directory")
    _files_to_keep(target, display, command, ())
    scratch = Path(tempfile.mkdtemp(prefix="rfc-keep-"))
    try:
        yield scratch
    finally:
        try:
            replace_directory(
                directory,
                display,
                lambda staging: shutil.copytree(scratch, staging, dirs_exist_ok=True),
                command,
            )
        finally:
            shutil.rmtree(scratch, ignore_errors=True)


def _files_to_keep(
    target: Path, display: str, command: str, inputs: Iterable[Path]
) -> dict[str, str]:
    """Files of `target` that must survive, each with why (an input, or not rfc's)."""
    if not target.is_dir() or not any(target.iterdir()):
        return {}
    owned = read_manifest(target)
    if owned is None:
        raise RfcError(
            f"output directory '{display}' holds files that {command} did not write; "
            "refusing to replace it",
            hint="choose another (new or empty) directory, or empty this one",
        )
    present = [path for path in files_under(target) if path != MARKER]
    kept = {path: "a file rfc did not write" for path in present if path not in owned}
    for given in inputs:
        resolved = given.resolve()
        if resolved != target and target not in resolved.parents:
            continue
        inside = "" if resolved == target else resolved.relative_to(target).as_posix() + "/"
        for path in present:
            if (path + "/").startswith(inside):
                kept[path] = "an input of this build"
    return kept


def _refuse_clashes(written: list[str], kept: dict[str, str], display: str, command: str) -> None:
    for path in written:
        parts = PurePosixPath(path).parts
        for depth in range(1, len(parts) + 1):
            prefix = "/".join(parts[:depth])
            if prefix in kept:
                raise RfcError(
                    f"{command} would write '{path}' in '{display}' over '{prefix}', "
                    f"which is {kept[prefix]}",
                    hint="move that file out of the output directory, or choose another -o",
                )


def _carry_over(source: Path, destination: Path) -> None:
    destination.parent.mkdir(parents=True, exist_ok=True)
    shutil.copy2(source, destination, follow_symlinks=False)


def _swap(staging: Path, target: Path) -> None:
    if not target.exists():
        staging.rename(target)
        return
    retired = Path(tempfile.mkdtemp(prefix=f".{target.name}.old.", dir=target.parent))
    retired.rmdir()
    target.rename(retired)
    try:
        staging.rename(target)
    except OSError:
        retired.rename(target)
        raise
    shutil.rmtree(retired, ignore_errors=True)
