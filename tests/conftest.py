"""Shared fixtures: the recorded data beside the checkout, and hypothesis profiles."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parent.parent
SHARED_DATA = Path(os.environ.get("RFC_SHARED_DATA", ROOT.parent / "shared" / "data"))

settings.register_profile(
    "rfc",
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    print_blob=True,
)
settings.load_profile("rfc")


def shared_file(relative: str) -> Path:
    """Return a file of the shared recorded data, skipping the test (saying why) when absent."""
    path = SHARED_DATA / relative
    if not path.exists():
        pytest.skip(f"recorded data {path} is absent on this machine (CI has it)")
    return path


@pytest.fixture
def examples_dir() -> Path:
    return ROOT / "examples"
