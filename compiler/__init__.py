"""rfc: from a compact robotics system description to an FPGA hardware/software architecture.

The Python front-end is available here (``rfc.Project``, ``@rfc.accelerator``,
``rfc.external_accelerator``, ``rfc.port``); it is imported on first use, so that ``import rfc``
stays fast.
"""

from __future__ import annotations

from typing import Any

__version__ = "0.1.0"

_LAZY = {
    "Project": "rfc.spec.python_project",
    "accelerator": "rfc.spec.python_accelerators",
    "external_accelerator": "rfc.spec.python_accelerators",
    "port": "rfc.spec.python_accelerators",
}
__all__ = ["Project", "__version__", "accelerator", "external_accelerator", "port"]


def __getattr__(name: str) -> Any:
    """Import the Python front-end on first use of one of its names."""
    if name in _LAZY:
        from importlib import import_module

        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'rfc' has no attribute '{name}'")
