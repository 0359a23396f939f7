"""A build of an unchanged spec converts nothing; any change to what the HDL depends on does."""

from __future__ import annotations

import importlib
import os
import struct
import sys
from pathlib import Path

import myhdl._block
from typer.testing import CliRunner

from rfc.cli import app
from rfc.driver import compile_spec
from rfc.lower.artifacts import BuildOptions
from rfc.lower.system.conversion_cache import (
    KEPT_VERSIONS,
    conversion_key,
    conversions_cached,
    project_modules,
    rfc_digest,
    source_digest,
)
from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.lower.system.systems import point_system, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
POINT = "geometry_msgs/msg/Point"

#: A Point → Point accelerator whose y is a constant of the module it imports.
ACCELERATOR = """from myhdl import always_comb, block
from {constants} import OFFSET


@block
def offset_point(clk, rst, in0_valid, in0_ready, in0_x, in0_y, in0_z,
                 out0_valid, out0_ready, out0_x, out0_y, out0_z):
    @always_comb
    def logic():
        out0_valid.next = in0_valid
        in0_ready.next = out0_ready
        out0_x.next = in0_{x}
        out0_y.next = OFFSET
        out0_z.next = in0_z

    return logic
"""


def project(folder: Path, constants: str, offset: int = 1, x: str = "x") -> Path:
    """The Point system around `offset_point`, its constant in module `constants`."""
    text = point_system("MyHDL", "offset.py", "offset_point")
    return write_spec(
        folder,
        text,
        offset__py=ACCELERATOR.format(constants=constants, x=x),
        **{f"{constants}__py": f"OFFSET = {offset}\n"},
    )


def files_below(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_a_second_build_converts_and_simulates_nothing_and_writes_the_first_ones_bytes(
    tmp_path, monkeypatch
):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    spec = project(tmp_path, "offsets_of_the_warm_build")
    cold = CliRunner().invoke(app, ["build", str(spec), "-o", str(tmp_path / "cold")])
    assert cold.exit_code == 0, cold.output

    def refuse(*args, **kwargs):
        raise AssertionError("a warm build converted or simulated a MyHDL block")

    # the report's latencies are measured in MyHDL's simulator: kept with the converted files
    monkeypatch.setattr(myhdl._block._Block, "convert", refuse)
    monkeypatch.setattr(myhdl._block._Block, "run_sim", refuse)
    warm = CliRunner().invoke(app, ["build", str(spec), "-o", str(tmp_path / "warm")])
    assert warm.exit_code == 0, warm.output
    assert files_below(tmp_path / "warm") == files_below(tmp_path / "cold")
    assert "hw/passpoint.vhd" in files_below(tmp_path / "warm")
    assert "| accelerator | `acc` | 1 |" in (tmp_path / "warm/report.md").read_text()


def test_a_second_sim_of_the_same_spec_converts_nothing_and_gives_the_first_ones_bag(
    tmp_path, monkeypatch
):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    spec = project(tmp_path, "offsets_of_the_warm_sim", offset=7)
    types = message_types("ros2")
    points = [types.build(POINT, {"x": float(n), "y": 0.0, "z": -float(n)}) for n in range(3)]
    bag = tmp_path / "in.mcap"
    write_bag(bag, types, {"/p": POINT}, [("/p", 1000 * (n + 1), types.serialize(p, POINT))
                                          for n, p in enumerate(points)])  # fmt: skip

    def sim(out: str) -> bytes:
        args = ["sim", str(spec), "--bag", str(bag), "--out", str(tmp_path / out)]
        result = CliRunner().invoke(app, [*args, "--simulator", "ghdl", "--json"])
        assert result.exit_code == 0, result.output
        return (tmp_path / out).read_bytes()

    cold = sim("cold.mcap")
    monkeypatch.setattr(myhdl._block._Block, "convert", refuse_to_convert)
    assert sim("warm.mcap") == cold
    # the accelerator's constant reached the bag: y is OFFSET's bits, not the input's 0.0
    outputs = [m.data for m in read_bag(tmp_path / "warm.mcap", types)]
    assert [types.deserialize(data, POINT).x for data in outputs] == [0.0, 1.0, 2.0]
    assert {struct.unpack_from("<Q", data, 12)[0] for data in outputs} == {7}


def refuse_to_convert(*args, **kwargs):
    raise AssertionError("a warm run converted a MyHDL block")


def test_a_changed_source_or_imported_module_is_converted_afresh(tmp_path):
    # in processes of their own, as users run them: an imported module is read afresh
    env = {"RFC_CACHE_DIR": str(tmp_path / "cache")}
    spec = project(tmp_path, "offsets", offset=3)
    accelerator = tmp_path / "build/hw/passpoint.vhd"

    def build() -> str:
        result = run_rfc("build", spec, "-o", tmp_path / "build", cwd=ROOT, env=env)
        assert result.returncode == 0, result.stderr
        return accelerator.read_text()

    assert "out0_y_num <= to_unsigned(3, 64);" in build()
    project(tmp_path, "offsets", offset=5)  # the imported module changes
    assert "out0_y_num <= to_unsigned(5, 64);" in build()
    project(tmp_path, "offsets", offset=5, x="y")  # the accelerator's own source changes
    assert "out0_x_num <= in0_y_num;" in build()


def test_the_key_changes_with_the_options_and_the_spec_not_with_the_projects_folder(tmp_path):
    spec = project(tmp_path, "offsets_of_the_key")
    (tmp_path / "copy").mkdir()
    copy = project(tmp_path / "copy", "offsets_of_the_key")
    design, copied = compile_spec(str(spec)), compile_spec(str(copy))
    key = conversion_key(spec, design, BuildOptions())
    assert conversion_key(spec, design, BuildOptions()) == key
    assert conversion_key(copy, copied, BuildOptions()) == key
    assert conversion_key(spec, design, BuildOptions(estimate=True)) != key
    spec.write_text(spec.read_text().replace("busWidth: 64", "busWidth: 32"))
    assert conversion_key(spec, design, BuildOptions()) != key


def test_rfcs_digest_covers_its_packages_and_changes_with_any_of_their_files(tmp_path):
    import rfc.lib
    import rfc.lower.system.components

    folders = [Path(p) for p in (*rfc.__path__, *rfc.lib.__path__)]
    assert rfc_digest() == source_digest(folders)
    assert any(Path(rfc.lower.system.components.__file__).is_relative_to(f) for f in folders)
    assert any(Path(rfc.lib.__file__).is_relative_to(f) for f in folders)

    package = tmp_path / "package"
    (package / "__pycache__").mkdir(parents=True)
    (package / "module.py").write_text("X = 1\n")
    (package / "cells.vhd").write_text("-- a template\n")
    before = source_digest([package])
    (package / "__pycache__/module.cpython-311.pyc").write_bytes(b"compiled")
    assert source_digest([package]) == before
    (package / "cells.vhd").write_text("-- another template\n")
    changed = source_digest([package])
    assert changed != before
    (package / "extra.py").write_text("")
    assert source_digest([package]) not in (before, changed)


def test_a_build_keeps_the_entries_of_the_rfc_versions_used_last_and_drops_older_ones(
    tmp_path, monkeypatch
):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path))
    older = [tmp_path / "conversion" / f"version{n}" for n in range(KEPT_VERSIONS)]
    for age, group in enumerate(older, start=1):
        (group / "entry").mkdir(parents=True)
        os.utime(group, (1e9 - age, 1e9 - age))  # version0 used last, the last one first
    with conversions_cached("a key"):
        pass
    kept = sorted(p.name for p in (tmp_path / "conversion").iterdir())
    assert len(kept) == KEPT_VERSIONS
    assert rfc_digest()[:24] in kept
    assert f"version{KEPT_VERSIONS - 1}" not in kept


def test_a_loaded_module_whose_file_is_gone_is_left_out_of_the_key(tmp_path, monkeypatch):
    # a process that built a temporary Python spec before (a test run, the wizard) still holds it
    gone = tmp_path / "spec_of_an_earlier_build.py"
    gone.write_text("VALUE = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.import_module(gone.stem)
    try:
        assert gone.resolve() in project_modules()
        gone.unlink()
        assert gone.resolve() not in project_modules()
    finally:
        del sys.modules[gone.stem]
