"""docs/accelerators.md's "Your first accelerator", step by step, so that it cannot rot.

The stub of the tutorial's spec builds as printed; the accelerator the doc shows is the one
the example ships; replayed through the generated logic in GHDL it mirrors every point exactly
as its reference says.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
EXAMPLE = ROOT / "examples/first_accelerator"


def documented(name: str) -> str:
    text = (ROOT / "docs/accelerators.md").read_text()
    found = re.search(rf"<!-- tutorial: {re.escape(name)} -->\n```python\n(.*?)```", text, re.S)
    assert found, f"docs/accelerators.md shows no {name}"
    return found.group(1)


def run(folder: Path, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, *args], cwd=folder, capture_output=True, text=True, check=False
    )


def test_the_documented_accelerator_is_the_one_the_example_ships():
    assert documented("mirror.py") == (EXAMPLE / "mirror.py").read_text()


def test_the_tutorial_from_stub_to_a_replayed_bag(tmp_path):
    folder = tmp_path / "my_first"
    shutil.copytree(EXAMPLE, folder)
    (folder / "mirror.py").unlink()

    stub = run_rfc("stub", "mirror.yaml", "Mirror", cwd=folder)
    assert stub.returncode == 0, stub.stderr
    assert "def mirror(clk, rst, p, m):" in stub.stdout
    (folder / "mirror.py").write_text(stub.stdout)
    built = run_rfc("build", "mirror.yaml", "-o", "build", cwd=folder)
    assert built.returncode == 0, built.stderr  # the skeleton builds as printed
    assert (folder / "build/hw/mirror.vhd").is_file()

    (folder / "mirror.py").write_text(documented("mirror.py"))
    made = run(folder, "points.py", "make", "points.mcap", "40")
    assert made.returncode == 0, made.stderr
    sim = run_rfc("sim", "mirror.yaml", "--bag", "points.mcap", "--out", "mirrored.mcap",
                  cwd=folder)  # fmt: skip
    assert sim.returncode == 0, sim.stderr
    compared = run(folder, "points.py", "compare", "points.mcap", "mirrored.mcap")
    assert compared.returncode == 0, compared.stdout + compared.stderr
    assert "40 of 40 points mirrored exactly" in compared.stdout
