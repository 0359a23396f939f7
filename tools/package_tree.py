"""Lay out the ``rfc`` package as Python sees it, for tools that walk directories.

pyproject maps ``rfc`` to compiler/, ``rfc.lib`` to lib/ and ``rfc.runtime`` to runtime/. The
editable install resolves that mapping with an import hook, which static tools (mypy, grimp,
import-linter) do not run: they look for ``rfc/lib/`` on disk. This builds that tree under
build/package-tree/ as symbolic links to the sources, so the tools read the files you edit.

Usage: .venv/bin/python tools/package_tree.py   (prints the directory to put on the path)
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TREE = ROOT / "build" / "package-tree"
# Where each package of the mapping lives in the checkout (pyproject's package-dir).
PACKAGE_DIRS = {"rfc": "compiler", "rfc/lib": "lib", "rfc/runtime": "runtime"}


def build_package_tree(root: Path = ROOT, tree: Path = TREE) -> Path:
    """Rebuild ``tree`` with a link per file of the mapping and return it (the path entry)."""
    if tree.exists():
        shutil.rmtree(tree)
    for package, directory in PACKAGE_DIRS.items():
        source = root / directory
        for file in source.rglob("*"):
            if file.is_dir() or "__pycache__" in file.parts:
                continue
            target = tree / package / file.relative_to(source)
            target.parent.mkdir(parents=True, exist_ok=True)
            target.symlink_to(file)
    return tree


def source_path(tree_path: str, root: Path = ROOT, tree: Path = TREE) -> str:
    """Map a path inside the tree back to the file in the checkout (for readable reports)."""
    path = Path(os.path.normpath(tree_path))
    try:
        relative = path.relative_to(tree)
    except ValueError:
        return os.path.relpath(path)
    for package, directory in sorted(PACKAGE_DIRS.items(), key=lambda item: -len(item[0])):
        try:
            rest = relative.relative_to(package)
        except ValueError:
            continue
        return os.path.relpath(root / directory / rest)
    return os.path.relpath(path)


if __name__ == "__main__":
    sys.stdout.write(f"{build_package_tree()}\n")
