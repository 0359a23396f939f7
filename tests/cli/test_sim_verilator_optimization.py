"""`RFC_VERILATOR_OPT` sets g++'s optimization of rfc's Verilator models, not what they compute.

The suite builds its models at ``0`` (tests/conftest.py); here the defaults build them too
(`rfc sim`'s at ``-O2``, `rfc msg loopback`'s at Verilator's own flags), and both levels must
give the same output bag and report, each model kept in the cache apart.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.lower.system.systems import PASS_THROUGH, point_system, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
POINT = "geometry_msgs/msg/Point"


def point_bag(path: Path) -> Path:
    types = message_types("ros2")
    messages = [
        (
            "/p",
            1000 * (i + 1),
            types.serialize(types.build(POINT, {"x": i + 0.5, "y": -2.0 * i, "z": 3.0}), POINT),
        )
        for i in range(5)
    ]
    write_bag(path, types, {"/p": POINT}, messages)
    return path


def verilator_sim(folder: Path, level: str, out: str) -> subprocess.CompletedProcess[str]:
    """`rfc sim` of the Point pass-through system on Verilator at optimization `level`."""
    system = point_system("MyHDL", "pass.py", "pass_through")
    spec = write_spec(folder, system, pass__py=PASS_THROUGH)
    bag = folder / "in.mcap"
    if not bag.exists():
        point_bag(bag)
    args = ("sim", spec, "--bag", bag, "--out", folder / out, "--simulator", "verilator")
    env = {"RFC_CACHE_DIR": str(folder / "cache"), "RFC_VERILATOR_OPT": level}
    return run_rfc(*args, cwd=folder, env=env)


def test_the_default_level_and_level_0_give_the_same_bag_from_two_models(tmp_path):
    default = verilator_sim(tmp_path, "", "default.mcap")  # unset: g++'s -O2
    assert default.returncode == 0, default.stderr
    quick = verilator_sim(tmp_path, "0", "quick.mcap")
    assert quick.returncode == 0, quick.stderr
    assert (tmp_path / "quick.mcap").read_bytes() == (tmp_path / "default.mcap").read_bytes()
    assert len(list(read_bag(tmp_path / "quick.mcap", message_types("ros2")))) == 5
    engines = sorted((tmp_path / "cache/verilator").glob("engine-*"))
    assert len(engines) == 2  # the level is part of the model's key
    builds = {engine: (engine / "Vdut").stat().st_mtime_ns for engine in engines}
    again = verilator_sim(tmp_path, "0", "again.mcap")
    assert again.returncode == 0, again.stderr
    assert {engine: (engine / "Vdut").stat().st_mtime_ns for engine in engines} == builds


def test_a_level_g_plus_plus_does_not_have_is_refused_and_nothing_is_written(tmp_path):
    result = verilator_sim(tmp_path, "fast", "out.mcap")
    assert result.returncode == 1
    assert "RFC_VERILATOR_OPT=fast is not an optimization level" in result.stderr
    assert "give one of 0, 1, 2, 3, s, g, or unset it" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "out.mcap").exists()


def verilator_loopback(folder: Path, level: str) -> subprocess.CompletedProcess[str]:
    """`rfc msg loopback` of five Points on Verilator at optimization `level`."""
    bag = folder / "in.mcap"
    if not bag.exists():
        point_bag(bag)
    args = ("msg", "loopback", POINT, "--bag", bag, "--simulator", "verilator", "--json")
    env = {"RFC_CACHE_DIR": str(folder / "cache"), "RFC_VERILATOR_OPT": level}
    return run_rfc(*args, cwd=folder, env=env)


def test_the_loopback_reports_the_same_bytes_and_cycles_at_both_levels(tmp_path):
    default = verilator_loopback(tmp_path, "")
    assert default.returncode == 0, default.stderr
    quick = verilator_loopback(tmp_path, "0")
    assert quick.returncode == 0, quick.stderr
    report = json.loads(default.stdout)
    assert json.loads(quick.stdout) == report
    assert report["equal"] is True
    assert len(list((tmp_path / "cache/verilator").glob("tb-*"))) == 2


def test_the_loopback_refuses_a_level_too(tmp_path):
    result = verilator_loopback(tmp_path, "9")
    assert result.returncode == 1
    assert "RFC_VERILATOR_OPT=9 is not an optimization level" in result.stderr
    assert "Traceback" not in result.stderr
