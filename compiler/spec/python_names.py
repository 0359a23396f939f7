"""The top-level functions a Python file defines, read without running it.

A spec's ``reference:`` names a function in a file; rfc checks that the function is there when
it reads the spec, so `rfc check` refuses a reference that `rfc sim` or a test would fail on.
"""

from __future__ import annotations

import ast
from pathlib import Path

from rfc.errors import RfcError, SourceLocation, did_you_mean


def check_defines(path: Path, name: str, what: str, location: SourceLocation) -> None:
    """Raise unless the Python file `path` defines `name` at its top level.

    Args:
        path: The Python file.
        name: The function's name.
        what: The spec value, for messages (``reference 'model.py:f'``).
        location: Where the spec names it.

    Raises:
        RfcError: `path` is not Python source, or defines no `name`.
    """
    if not path.exists():
        return  # a source `rfc stub` is asked to write: nothing to check yet
    try:
        tree = ast.parse(path.read_bytes(), filename=str(path))
    except (SyntaxError, ValueError, UnicodeDecodeError) as exc:
        raise RfcError(
            f"{what}: '{path.name}' is not a Python source ({exc.__class__.__name__})",
            location=location,
            hint="name a .py file holding the function",
        ) from None
    defined = _top_level_names(tree)
    if name not in defined:
        raise RfcError(
            f"{what}: '{path.name}' defines no function '{name}'",
            location=location,
            hint=did_you_mean(name, defined)
            or f"its functions are {', '.join(sorted(defined)) or 'none'}",
        )


def _top_level_names(tree: ast.Module) -> list[str]:
    names: list[str] = []
    for node in tree.body:
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.append(node.name)
        elif isinstance(node, ast.Assign):
            names += [t.id for t in node.targets if isinstance(t, ast.Name)]
        elif isinstance(node, ast.AnnAssign | ast.AugAssign) and isinstance(node.target, ast.Name):
            names.append(node.target.id)
        elif isinstance(node, ast.ImportFrom | ast.Import):
            names += [alias.asname or alias.name.split(".")[0] for alias in node.names]
    return names
