"""Writing the build's artifacts into the output directory all at once, or not at all.

The directory is replaced through `rfc.files.directory`, which the DSE and the other commands
share: an error or Ctrl-C on the way leaves the target as it was, and only the files rfc wrote
last time are deleted.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from pathlib import Path, PurePosixPath

from rfc.files.directory import replace_directory
from rfc.lower.artifacts import Artifact

__all__ = ["write_artifacts"]


def write_artifacts(
    artifacts: Sequence[Artifact], directory: Path, display: str, inputs: Iterable[Path] = ()
) -> None:
    """Replace rfc's files in `directory` with exactly `artifacts`.

    Args:
        artifacts: The files to write.
        directory: The output directory.
        display: How to name it in messages.
        inputs: Files and directories the build read; never overwritten nor deleted.

    Raises:
        RfcError: The directory is not rfc's, cannot be written, or a file would replace an
            input or a file rfc did not write.
    """

    def fill(staging: Path) -> None:
        for artifact in artifacts:
            path = staging.joinpath(*PurePosixPath(artifact.path).parts)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(artifact.text, encoding="utf-8")

    replace_directory(directory, display, fill, inputs=inputs)
