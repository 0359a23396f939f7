"""numba's compiler as the scheduler kernels use it, typed: mypy sees each kernel's signature.

numba's own `njit` declares neither the options used here nor what it returns for them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

from numba import njit

Function = TypeVar("Function", bound=Callable[..., Any])

#: On disk, so that a new process loads a kernel instead of compiling it; without numba's
#: reference-counting runtime, which kernels that allocate nothing do not need.
_OPTIONS: dict[str, Any] = {"cache": True, "_nrt": False}


def kernel(function: Function) -> Function:
    """`function` compiled on its first call (plain Python under ``NUMBA_DISABLE_JIT=1``)."""
    return cast(Function, njit(**_OPTIONS)(function))
