"""Fixtures shared by the system lowering tests."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def synthesis_cache(tmp_path_factory):
    """One cache of module figures for every `--estimate` of the session: each module is mapped
    once, whichever test builds it first (the quaternion accelerator is shared by several)."""
    return tmp_path_factory.mktemp("synthesis-cache")
