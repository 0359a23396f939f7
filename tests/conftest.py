"""Shared fixtures: the recorded data beside the checkout, hypothesis profiles, MyHDL hygiene."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

from rfc.toolchain.myhdl_state import transient_signals
from rfc.toolchain.verilator import compiler_cache

ROOT = Path(__file__).resolve().parent.parent
SHARED_DATA = Path(os.environ.get("RFC_SHARED_DATA", ROOT.parent / "shared" / "data"))

settings.register_profile(
    "rfc",
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    print_blob=True,
)
settings.load_profile("rfc")

# `rfc sim` runs GHDL's fastest back-end, llvm, which compiles each new logic to a program
# (about 10 s of CPU, cached). The suite builds hundreds of distinct logics once each, where
# mcode's analysis is cheaper than llvm's compile; tests/cli/test_sim_ghdl_cache.py and
# tests/toolchain/test_ghdl_*.py run llvm itself and check it gives mcode's bytes.
os.environ.setdefault("GHDL_BACKEND", "mcode")
# Likewise the Verilator models: the suite builds dozens and replays a few messages through
# each, where g++'s -O0 builds Franka's in 29 s against 67 s at `rfc sim`'s default -O2. The
# long replays unset it; tests/cli/test_sim_verilator_optimization.py compares both levels.
os.environ.setdefault("RFC_VERILATOR_OPT", "0")

# Tests that keep their compiled models apart (their own RFC_CACHE_DIR) still share the objects
# every Verilator build compiles alike: ccache answers by content, it cannot mix results.
for _key, _value in compiler_cache().items():
    os.environ.setdefault(_key, _value)


@pytest.fixture(autouse=True)
def myhdl_signals_die_with_their_test() -> Iterator[None]:
    """MyHDL forgets each test's signals after it (`rfc.toolchain.transient_signals`).

    Otherwise a worker keeps every signal of every test it ran and resets all of them at the end
    of each simulation: a hypothesis test of 25 small simulations took 278 s late in a run of the
    suite, 2 s alone. Wider-scoped fixtures are set up before this one, so their signals stay.
    """
    with transient_signals():
        yield


def shared_file(relative: str) -> Path:
    """Return a file of the shared recorded data, skipping the test (saying why) when absent."""
    path = SHARED_DATA / relative
    if not path.exists():
        pytest.skip(f"recorded data {path} is absent on this machine (CI has it)")
    return path


@pytest.fixture
def examples_dir() -> Path:
    return ROOT / "examples"
