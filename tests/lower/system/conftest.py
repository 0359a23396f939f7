"""Fixtures shared by the system lowering tests."""

from __future__ import annotations

import pytest

from rfc.toolchain.cache import cache_root


@pytest.fixture(scope="session")
def synthesis_cache():
    """The user's rfc cache (``$RFC_CACHE_DIR`` or ``~/.cache/rfc``), for every `--estimate`.

    Module figures are kept by the content of the module's Verilog, the flow and Yosys's
    version, so a module the cache holds gives the figures a fresh mapping would: a session
    maps only the modules no earlier run (a build, the suite in another clone) mapped, and a
    worker that needs a module another is mapping waits for it. The mapping itself is tested
    with fresh caches (tests/toolchain).
    """
    cache = cache_root()
    cache.mkdir(parents=True, exist_ok=True)
    return cache
