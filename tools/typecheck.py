"""mypy --strict on the whole package ([tool.mypy] of pyproject.toml), reporting source paths.

mypy reads the package from the tree `package_tree.py` lays out (the editable install's import
hook is invisible to it); its report names the files you edit. Exit status: mypy's.

Usage: .venv/bin/python tools/typecheck.py            the package (the lint step runs this)
       .venv/bin/python tools/typecheck.py -m rfc.lib.slice   anything else mypy accepts
"""

from __future__ import annotations

import re
import subprocess
import sys

from package_tree import ROOT, TREE, build_package_tree, source_path

_PATH = re.compile(r"^(\S+\.pyi?)(?=:)", re.MULTILINE)


def typecheck(arguments: list[str]) -> int:
    """Run mypy with `arguments` on a fresh package tree; print its report with source paths."""
    build_package_tree()
    mypy = [sys.executable, "-m", "mypy", "--config-file", str(ROOT / "pyproject.toml")]
    run = subprocess.run([*mypy, *arguments], cwd=TREE, capture_output=True, text=True, check=False)
    sys.stdout.write(_PATH.sub(lambda match: source_path(str(TREE / match.group(1))), run.stdout))
    sys.stderr.write(run.stderr)
    return run.returncode


if __name__ == "__main__":
    sys.exit(typecheck(sys.argv[1:]))
