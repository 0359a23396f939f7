"""Front-ends: a YAML or Python system specification becomes a `Design` (stage PARSED).

Layer: below the passes; it may import `rfc.ir` and the layers under it.
"""

from __future__ import annotations

from pathlib import Path

from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.spec.text_files import binary_reason

#: Spec formats by file suffix.
SPEC_SUFFIXES = (".yaml", ".yml", ".py")


def load_spec(path: Path, display: str | None = None) -> Design:
    """Read a spec file with the front-end its suffix names.

    Args:
        path: A ``.yaml``/``.yml`` or ``.py`` spec.
        display: How to name the file in error locations (default: `path` as given).

    Raises:
        RfcError: The file is missing, of an unknown kind, or not a valid spec.
    """
    display = display or str(path)
    if not path.is_file():
        raise RfcError(f"spec '{display}' does not exist")
    suffix = path.suffix.lower()
    if suffix in SPEC_SUFFIXES:
        _refuse_binary(path, display)
    if suffix in (".yaml", ".yml"):
        from rfc.spec.yaml_frontend import load_yaml_spec

        return load_yaml_spec(path, display)
    if suffix == ".py":
        from rfc.spec.python_loader import load_python_spec

        return load_python_spec(path, display)
    raise RfcError(
        f"spec '{display}' is neither YAML nor Python; expected a file ending in "
        f"{', '.join(SPEC_SUFFIXES)}"
    )


def _refuse_binary(path: Path, display: str) -> None:
    """A spec is UTF-8 text without NUL bytes; say so plainly for anything else."""
    try:
        reason = binary_reason(path)
    except OSError as exc:
        raise RfcError(f"cannot read spec '{display}': {exc.strerror}") from None
    if reason is not None:
        raise RfcError(
            f"'{display}' is not a spec: it is binary, not YAML or Python text ({reason})",
            hint="give the .yaml or .py file that describes the system",
        )
