"""GHDL's back-end: the fastest one installed, unless ``GHDL_BACKEND`` names one."""

from __future__ import annotations

import subprocess

import pytest

from rfc.toolchain.ghdl import backend_named, fastest_backend


@pytest.fixture(autouse=True)
def _fresh():
    fastest_backend.cache_clear()
    yield
    fastest_backend.cache_clear()


def generator(backend: str) -> str:
    """What GHDL itself says it generates code with under `backend`."""
    env = {"GHDL_BACKEND": backend, "PATH": "/usr/bin:/bin"}
    return subprocess.run(["ghdl", "--version"], capture_output=True, text=True, env=env).stdout


def test_the_llvm_back_end_set_up_installs_is_the_one_chosen(monkeypatch):
    monkeypatch.delenv("GHDL_BACKEND", raising=False)
    backend = fastest_backend()
    assert backend.name == "llvm"
    assert backend.compiles
    assert "llvm code generator" in generator("llvm")
    assert backend.version == generator("llvm").splitlines()[0]


def test_ghdl_backend_names_another(monkeypatch):
    monkeypatch.setenv("GHDL_BACKEND", "mcode")
    backend = fastest_backend()
    assert backend.name == "mcode"
    assert not backend.compiles
    assert "mcode code generator" in generator("mcode")


def test_a_back_end_asked_for_by_name_is_that_one_whatever_ghdl_backend_says(monkeypatch):
    monkeypatch.setenv("GHDL_BACKEND", "mcode")
    backend_named.cache_clear()
    llvm = backend_named("llvm")
    assert llvm is not None
    assert llvm.name == "llvm"
    assert llvm.version == generator("llvm").splitlines()[0]
    assert backend_named("nvc") is None
