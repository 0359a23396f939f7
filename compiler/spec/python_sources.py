"""Importing an accelerator's Python source file: its MyHDL block or its ROS-SW function.

The file is imported once per path, with its own directory on ``sys.path`` while it runs (so it
can import the modules beside it); an error it raises becomes an `RfcError` at the accelerator,
never a traceback.
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from rfc.errors import RfcError
from rfc.ir.model import AcceleratorType
from rfc.user_code import running_user_code


def function_in(
    path: Path, name: str, accelerator: AcceleratorType, role: str
) -> Callable[..., Any]:
    """The callable `name` defined in `path`.

    Args:
        path: The Python source.
        name: The function's name.
        accelerator: The accelerator it is for (for messages).
        role: What the function is, for messages (``ROS-SW accelerator``, ``MyHDL block``).

    Raises:
        RfcError: The file fails to import or defines no such callable.
    """
    module = import_file(path, accelerator)
    function: object = getattr(module, name, None)
    if not callable(function):
        raise RfcError(
            f"'{path.name}' defines no function '{name}' for {role} '{accelerator.name}'",
            location=accelerator.location,
            hint="name it with 'top:' or 'reference: file.py:function'",
        )
    return function


def import_file(path: Path, accelerator: AcceleratorType) -> Any:
    """Import `path` as a module (cached by its resolved path)."""
    name = f"_rfc_source_{abs(hash(str(path.resolve())))}"
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise RfcError(f"cannot load '{path}'", location=accelerator.location)
    module = importlib.util.module_from_spec(spec)
    directory = str(path.resolve().parent)
    sys.path.insert(0, directory)
    try:
        with running_user_code(
            f"importing '{path.name}' for accelerator '{accelerator.name}'", accelerator.location
        ):
            spec.loader.exec_module(module)
    except RfcError:
        raise
    except Exception as exc:  # the user's module failed to import: report it, no traceback
        raise RfcError(
            f"importing '{path.name}' for accelerator '{accelerator.name}' raised "
            f"{type(exc).__name__}: {exc}",
            location=accelerator.location,
        ) from None
    finally:
        sys.path.remove(directory)
    sys.modules[name] = module
    return module
