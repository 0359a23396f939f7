"""Check the import contracts of pyproject.toml ([tool.importlinter]) against the sources.

import-linter walks the package on disk, so it reads the tree `package_tree.py` lays out (the
editable install's import hook is invisible to it). Exit status: import-linter's (0 = kept).

Usage: .venv/bin/python tools/lint_layers.py [lint-imports options]
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from package_tree import ROOT, build_package_tree


def lint_layers(arguments: list[str], root: Path = ROOT) -> int:
    """Run lint-imports on a fresh package tree of `root` with its pyproject's contracts."""
    tree = build_package_tree(root, root / "build" / "package-tree")
    lint_imports = Path(sys.executable).parent / "lint-imports"
    environment = {**os.environ, "PYTHONPATH": str(tree)}
    command = [str(lint_imports), str(root / "pyproject.toml"), "--no-cache"]
    return subprocess.run([*command, *arguments], cwd=tree, env=environment, check=False).returncode


if __name__ == "__main__":
    sys.exit(lint_layers(sys.argv[1:]))
