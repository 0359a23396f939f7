"""`rfc sim --simulator ghdl` compiles the logic once per build and reuses it in later runs.

GHDL's llvm back-end (which tools/setup.sh installs) compiles the logic to a program kept in
the rfc cache by the content of its VHDL; the mcode back-end, which compiles the logic in
memory at every run, is the reference the compiled program's outputs must equal byte for byte.
"""

from __future__ import annotations

from pathlib import Path

from rfc.messages.rosbags_adapter import message_types, write_bag
from tests.runtime.support import pose_messages, system_copy
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
ECHO = ("--top-provider", "tests.runtime.echo_top:simulation_top")
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"
COMPILES = "GHDL's llvm back-end compiles the logic, once"
REUSES = "GHDL's llvm back-end runs the logic compiled before"


def pose_bag(path: Path) -> Path:
    types = message_types("ros2")
    messages = pose_messages(types, 3)
    write_bag(
        path, types, {"/amcl_pose": POSE}, [(m.topic, m.timestamp_ns, m.data) for m in messages]
    )
    return path


def ghdl_sim(spec: Path, bag: Path, out: Path, cache: Path, backend: str = "") -> str:
    """Run `rfc sim` on GHDL with its own cache; its standard error."""
    env = {"RFC_CACHE_DIR": str(cache), "GHDL_BACKEND": backend}
    args = ("sim", spec, "--bag", bag, "--out", out, "--simulator", "ghdl", "--json", *ECHO)
    result = run_rfc(*args, "--drain-cycles", "200", cwd=ROOT, env=env)
    assert result.returncode == 0, result.stderr
    return result.stderr


def programs(cache: Path) -> dict[Path, tuple[int, int]]:
    """Every compiled program in the cache, with its inode and modification time."""
    found = {}
    for entry in (cache / "ghdl").iterdir():
        for path in entry.iterdir():
            if path.is_file() and path.stat().st_mode & 0o111:
                found[path] = (path.stat().st_ino, path.stat().st_mtime_ns)
    return found


def test_a_second_run_of_the_same_build_reuses_the_compiled_logic(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    bag = pose_bag(tmp_path / "in.mcap")
    cache = tmp_path / "cache"
    first = ghdl_sim(spec, bag, tmp_path / "first.mcap", cache)
    assert COMPILES in first
    compiled = programs(cache)
    assert len(compiled) == 1
    second = ghdl_sim(spec, bag, tmp_path / "second.mcap", cache)
    assert REUSES in second
    assert COMPILES not in second
    assert programs(cache) == compiled  # the very program, not compiled again
    reference = ghdl_sim(spec, bag, tmp_path / "mcode.mcap", tmp_path / "mcode", "mcode")
    assert "mcode back-end" in reference
    assert not (tmp_path / "mcode" / "ghdl").exists()
    expected = (tmp_path / "mcode.mcap").read_bytes()
    assert (tmp_path / "first.mcap").read_bytes() == expected
    assert (tmp_path / "second.mcap").read_bytes() == expected


def test_a_changed_build_is_compiled_again(tmp_path):
    bag = pose_bag(tmp_path / "in.mcap")
    cache = tmp_path / "cache"
    (tmp_path / "wide").mkdir()
    (tmp_path / "narrow").mkdir()
    wide = system_copy(tmp_path / "wide", "pose_mixed.yaml")
    assert COMPILES in ghdl_sim(wide, bag, tmp_path / "wide.mcap", cache)
    # the same system on a 32-bit bus: other logic
    narrow = system_copy(tmp_path / "narrow", "pose_mixed.yaml", ("busWidth: 64", "busWidth: 32"))
    assert COMPILES in ghdl_sim(narrow, bag, tmp_path / "narrow.mcap", cache)
    assert len(programs(cache)) == 2
    assert (tmp_path / "narrow.mcap").read_bytes() == (tmp_path / "wide.mcap").read_bytes()
