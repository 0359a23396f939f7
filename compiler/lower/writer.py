"""Writing artifacts into the output directory all at once, or not at all.

Everything is written into a fresh staging directory beside the target, which then replaces
the target in one rename; an error on the way leaves the target as it was. A directory that
holds files rfc did not write is never replaced.
"""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path, PurePosixPath

from rfc.errors import RfcError
from rfc.lower.artifacts import Artifact

#: The file that marks a directory as written by ``rfc build`` (and so safe to replace).
MARKER = ".rfc-build"


def write_artifacts(artifacts: Sequence[Artifact], directory: Path, display: str) -> None:
    """Replace `directory` with one holding exactly `artifacts`.

    Args:
        artifacts: The files to write.
        directory: The output directory.
        display: How to name it in messages.

    Raises:
        RfcError: The directory exists but is not an rfc build directory, or cannot be written.
    """

    def fill(staging: Path) -> None:
        for artifact in artifacts:
            path = staging.joinpath(*PurePosixPath(artifact.path).parts)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(artifact.text, encoding="utf-8")

    replace_directory(directory, display, fill)


def replace_directory(
    directory: Path, display: str, fill: Callable[[Path], None], command: str = "rfc build"
) -> None:
    """Replace `directory` by a staging directory that `fill` writes, or leave it untouched.

    Args:
        directory: The output directory.
        display: How to name it in messages.
        fill: Writes the files into the staging directory it is given (text or binary).
        command: The command writing it, for messages.

    Raises:
        RfcError: The directory exists but was not written by rfc, or cannot be written.
    """
    target = directory.resolve()
    if target.exists() and not target.is_dir():
        raise RfcError(f"output '{display}' exists and is not a directory")
    if target.exists() and not (target / MARKER).exists() and any(target.iterdir()):
        raise RfcError(
            f"output directory '{display}' holds files that {command} did not write; "
            "refusing to replace it",
            hint="choose another directory with -o, or empty this one",
        )
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=target.parent))
        staging.chmod(0o755)  # mkdtemp makes it private; a build directory is not
    except OSError as exc:
        raise RfcError(f"cannot create output directory '{display}': {exc}") from None
    try:
        fill(staging)
        (staging / MARKER).write_text(f"written by {command}; the whole directory is replaced\n")
        _swap(staging, target)
    except OSError as exc:
        raise RfcError(f"cannot write output directory '{display}': {exc}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


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
