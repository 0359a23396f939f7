"""docs/tutorial.md runs as written: its files are written, its commands run, in a fresh folder.

Blocks fenced ``python file=NAME`` or ``text file=NAME`` are written to NAME; every line of a
``sh`` block is run (``rfc`` as this checkout's command line, ``python`` as this interpreter)
and must succeed. The ``sh install`` block is what made this checkout usable, so instead of
re-running it (it needs root and the network) the test checks what it leaves behind: rfc
importable from this checkout, GHDL on the PATH.
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import rfc
from rfc.messages.rosbags_adapter import message_types, read_bag

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "docs" / "tutorial.md"
BLOCK = re.compile(r"^```(\w+)(?: (\S+))?\n(.*?)^```$", re.MULTILINE | re.DOTALL)


def blocks() -> list[tuple[str, str, str]]:
    return BLOCK.findall(TUTORIAL.read_text(encoding="utf-8"))


def command(line: str) -> list[str]:
    words = shlex.split(line)
    if words[0] == "rfc":
        return [sys.executable, "-m", "rfc", *words[1:]]
    if words[0] == "python":
        return [sys.executable, *words[1:]]
    return words


def test_the_install_block_is_what_this_checkout_has():
    (install,) = [text for kind, extra, text in blocks() if (kind, extra) == ("sh", "install")]
    assert "pip install -e ." in install
    assert Path(rfc.__file__).resolve().is_relative_to(ROOT)
    assert shutil.which("ghdl") is not None


def test_the_tutorial_runs_from_an_empty_folder_to_a_simulated_system(tmp_path):
    folder = tmp_path
    for kind, extra, text in blocks():
        if extra.startswith("file="):
            (folder / extra.removeprefix("file=")).write_text(text, encoding="utf-8")
        elif kind == "sh" and extra != "install":
            for line in text.splitlines():
                line = line.split("#")[0].strip()
                if not line:
                    continue
                done = subprocess.run(
                    command(line), cwd=folder, capture_output=True, text=True, check=False
                )
                assert done.returncode == 0, f"{line}\n{done.stdout}\n{done.stderr}"
                if line == "mkdir -p doubler":
                    folder = folder / "doubler"
    spec = (folder / "project.yaml").read_text()
    assert "type: MyHDL" in spec
    assert "type: ROS-SW" in spec
    # the oracle: the points written, doubled in Python
    types = message_types("ros2")
    point = "geometry_msgs/msg/Point"
    sent = [
        types.deserialize(m.data, point) for m in read_bag(folder / "points/points.mcap", types)
    ]
    got = [types.deserialize(m.data, point) for m in read_bag(folder / "doubled.mcap", types)]
    assert [(p.x, p.y, p.z) for p in got] == [(2 * p.x, 2 * p.y, 2 * p.z) for p in sent]
    assert len(got) == 5
