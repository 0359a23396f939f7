"""The documentation stands alone: every relative link resolves, nothing cites a private file."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCUMENTS = sorted([ROOT / "README.md", *(ROOT / "docs").rglob("*.md")])
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def _relative_targets(document: Path) -> list[str]:
    targets = LINK.findall(document.read_text(encoding="utf-8"))
    return [t for t in targets if not re.match(r"[a-z]+:", t) and not t.startswith("#")]


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_point_at_files_in_the_repository(document: Path) -> None:
    missing = [
        target
        for target in _relative_targets(document)
        if not (document.parent / target.split("#")[0]).exists()
    ]
    assert missing == []


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_document_cites_the_private_design_brief(document: Path) -> None:
    text = document.read_text(encoding="utf-8")
    assert "DESIGN.md" not in text
    assert "shared/data" not in text


def test_link_checker_sees_the_links_of_the_readme() -> None:
    targets = {t.split("#")[0] for t in _relative_targets(ROOT / "README.md")}
    assert {"docs/architecture.md", "docs/spec.md"} <= targets
