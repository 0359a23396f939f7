"""The image pipeline example's folder, and its modules as the tests import them."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path
from types import ModuleType

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "image_pipeline"


def example_module(name: str) -> ModuleType:
    """A module of the example (its modules import each other by plain name)."""
    if str(EXAMPLE) not in sys.path:
        sys.path.insert(0, str(EXAMPLE))
    return importlib.import_module(name)
