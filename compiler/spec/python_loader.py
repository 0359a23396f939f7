"""Running a Python spec file and finding the `rfc.Project` it defines.

The file runs as a module with its own directory on ``sys.path`` (so that it can import the
accelerators beside it). Errors it raises become `RfcError`s at the failing line of the user's
code, never a traceback.
"""

from __future__ import annotations

import importlib.util
import sys
import traceback
from pathlib import Path

from rfc.errors import RfcError, SourceLocation
from rfc.ir.model import Design
from rfc.spec.python_project import Project
from rfc.user_code import running_user_code


def load_python_spec(path: Path, display: str | None = None) -> Design:
    """Run a Python spec and return its project's design at stage PARSED.

    Args:
        path: The ``.py`` file.
        display: How to name the file in locations (default: the path as given).

    Raises:
        RfcError: The file fails to run, or defines no project or several.
    """
    display = display or str(path)
    module_name = f"_rfc_spec_{abs(hash(str(path.resolve())))}"
    spec = importlib.util.spec_from_file_location(module_name, display)
    if spec is None or spec.loader is None:
        raise RfcError(f"cannot load Python spec '{display}'")
    module = importlib.util.module_from_spec(spec)
    directory = str(path.resolve().parent)
    sys.path.insert(0, directory)
    sys.modules[module_name] = module
    try:
        with running_user_code(f"the Python spec '{display}'"):
            spec.loader.exec_module(module)
    except RfcError:
        raise
    except SyntaxError as exc:
        file = _name(exc.filename or display, path, display)
        raise RfcError(
            f"Python syntax error: {exc.msg}",
            location=SourceLocation(file, exc.lineno or 1, exc.offset or 1),
        ) from None
    except Exception as exc:  # the user's code failed: report it at its line, no traceback
        raise RfcError(
            f"the spec raised {type(exc).__name__}: {exc}",
            location=_failing_line(exc, path, display),
        ) from None
    finally:
        sys.path.remove(directory)
    projects = list({id(v): v for v in vars(module).values() if isinstance(v, Project)}.values())
    if not projects:
        raise RfcError(
            f"'{display}' defines no rfc.Project",
            location=SourceLocation(display, 1, 1),
            hint="create one at module level: project = rfc.Project('Name', ...)",
        )
    if len(projects) > 1:
        names = ", ".join(f"'{p.name}'" for p in projects)
        raise RfcError(
            f"'{display}' defines {len(projects)} projects ({names}); rfc builds one per file",
            location=SourceLocation(display, 1, 1),
        )
    return projects[0].design()


def _name(filename: str, path: Path, display: str) -> str:
    """Name the spec file as the user gave it, other files as Python reports them."""
    return display if Path(filename).resolve() == path.resolve() else filename


def _failing_line(exc: BaseException, path: Path, display: str) -> SourceLocation | None:
    """The deepest frame of the traceback that is in the spec file."""
    found = None
    for frame in traceback.extract_tb(exc.__traceback__):
        if Path(frame.filename).resolve() == path.resolve():
            found = SourceLocation(display, frame.lineno or 1, (frame.colno or 0) + 1)
    return found
