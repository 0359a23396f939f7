"""Fixtures shared by the system lowering tests."""

from __future__ import annotations

import os

import pytest


@pytest.fixture(scope="session")
def synthesis_cache(tmp_path_factory):
    """One cache of module figures for every `--estimate` of the session, shared by its workers.

    Each module is mapped once, by whichever test builds it first (the quaternion accelerator
    is shared by several; a worker that needs a module another is mapping waits for it); the
    cache is written whole or not at all, so workers may share it.
    """
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent  # the session's folder, above each worker's own
    cache = root / "synthesis-cache"
    cache.mkdir(exist_ok=True)
    return cache
