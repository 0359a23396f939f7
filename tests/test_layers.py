"""The import contracts of pyproject.toml: rfc's layers only point down (docs/architecture.md)."""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TOOLS = ROOT / "tools"


@pytest.fixture
def lint_layers(monkeypatch):
    monkeypatch.syspath_prepend(str(TOOLS))
    spec = importlib.util.spec_from_file_location("lint_layers", TOOLS / "lint_layers.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.lint_layers


def copy_of_the_sources(destination: Path) -> Path:
    for directory in ("compiler", "lib", "runtime"):
        shutil.copytree(
            ROOT / directory, destination / directory, ignore=shutil.ignore_patterns("__pycache__")
        )
    shutil.copy(ROOT / "pyproject.toml", destination / "pyproject.toml")
    return destination


def test_the_sources_keep_every_import_contract(lint_layers, tmp_path, capfd):
    status = lint_layers([], copy_of_the_sources(tmp_path))
    report = capfd.readouterr().out
    assert status == 0, report
    assert "Contracts: 3 kept, 0 broken." in report


def test_a_module_importing_a_higher_layer_breaks_the_contract(lint_layers, tmp_path, capfd):
    root = copy_of_the_sources(tmp_path)
    (root / "compiler" / "messages" / "upward.py").write_text(
        '"""Reaches up from the bottom."""\n\nfrom rfc.lower.writer import write_artifacts\n'
    )
    status = lint_layers([], root)
    report = capfd.readouterr().out
    assert status == 1
    assert "rfc.messages is not allowed to import rfc.lower" in report
    assert "rfc.messages.upward -> rfc.lower.writer" in report
