"""The output directory: rfc deletes only what its manifest lists, and a build is all or nothing."""

from __future__ import annotations

from pathlib import Path

import pytest

from rfc.errors import RfcError
from rfc.files.directory import kept_in, replace_directory
from rfc.files.manifest import HEADER, MARKER


def _writer(files: dict[str, str]):
    def fill(staging: Path) -> None:
        for name, text in files.items():
            (staging / name).parent.mkdir(parents=True, exist_ok=True)
            (staging / name).write_text(text)

    return fill


def _tree(directory: Path) -> dict[str, str]:
    return {
        p.relative_to(directory).as_posix(): p.read_text()
        for p in sorted(directory.rglob("*"))
        if p.is_file()
    }


def test_the_manifest_lists_exactly_the_files_written(tmp_path):
    out = tmp_path / "out"
    replace_directory(out, "out", _writer({"a.vhd": "a", "hw/b.vhd": "b"}))
    assert (out / MARKER).read_text().splitlines() == [HEADER, "a.vhd", "hw/b.vhd"]


def test_a_rebuild_deletes_the_last_builds_files_and_keeps_the_users(tmp_path):
    out = tmp_path / "out"
    replace_directory(out, "out", _writer({"old.vhd": "old", "hw/b.vhd": "b"}))
    (out / "notes.txt").write_text("mine")
    (out / "hw" / "patch.vhd").write_text("mine too")
    replace_directory(out, "out", _writer({"hw/b.vhd": "new b"}))
    assert _tree(out) == {
        MARKER: f"{HEADER}\nhw/b.vhd\n",
        "hw/b.vhd": "new b",
        "hw/patch.vhd": "mine too",
        "notes.txt": "mine",
    }
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_a_file_written_over_a_users_file_is_an_error_and_changes_nothing(tmp_path):
    out = tmp_path / "out"
    replace_directory(out, "out", _writer({"a.vhd": "a"}))
    (out / "b.vhd").write_text("mine")
    before = _tree(out)
    with pytest.raises(RfcError, match=r"over 'b\.vhd', which is a file rfc did not write"):
        replace_directory(out, "out", _writer({"b.vhd": "generated"}))
    assert _tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_an_input_inside_the_output_is_never_overwritten(tmp_path):
    out = tmp_path / "out"
    replace_directory(out, "out", _writer({"model.yaml": "generated"}))
    spec = out / "model.yaml"  # a generated file the user now builds from
    with pytest.raises(RfcError, match=r"over 'model\.yaml', which is an input of this build"):
        replace_directory(out, "out", _writer({"model.yaml": "again"}), inputs=[spec])
    assert spec.read_text() == "generated"


def test_an_input_the_manifest_lists_survives_a_build_that_no_longer_writes_it(tmp_path):
    out = tmp_path / "out"
    replace_directory(out, "out", _writer({"spec.yaml": "spec", "sources/a.vhd": "a"}))
    replace_directory(
        out, "out", _writer({"x.vhd": "x"}), inputs=[out / "spec.yaml", out / "sources"]
    )
    assert _tree(out)["spec.yaml"] == "spec"
    assert _tree(out)["sources/a.vhd"] == "a"


@pytest.mark.parametrize(
    "marker",
    [
        pytest.param(lambda m: m.mkdir(), id="a directory"),
        pytest.param(lambda m: m.write_text("anything\n"), id="other text"),
        pytest.param(lambda m: m.write_text(f"{HEADER}\n../outside\n"), id="a path outside"),
        pytest.param(lambda m: m.symlink_to(m.parent / "real"), id="a symlink"),
    ],
)
def test_a_marker_that_is_not_a_manifest_makes_the_directory_the_users(tmp_path, marker):
    out = tmp_path / "out"
    out.mkdir()
    (out / "real").write_text(f"{HEADER}\nreal\n")
    (out / "thesis.tex").write_text("mine")
    marker(out / MARKER)
    with pytest.raises(RfcError, match="holds files that rfc build did not write"):
        replace_directory(out, "out", _writer({"a.vhd": "a"}))
    assert (out / "thesis.tex").read_text() == "mine"
    assert (out / "real").exists()


def test_an_interrupted_build_leaves_the_previous_one_intact(tmp_path):
    out = tmp_path / "out"
    replace_directory(out, "out", _writer({"a.vhd": "a"}))
    before = _tree(out)

    def interrupted(staging: Path) -> None:
        (staging / "a.vhd").write_text("half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        replace_directory(out, "out", interrupted)
    assert _tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_an_empty_directory_is_used_and_a_file_is_refused(tmp_path):
    (tmp_path / "empty").mkdir()
    replace_directory(tmp_path / "empty", "empty", _writer({"a.vhd": "a"}))
    assert (tmp_path / "empty" / "a.vhd").read_text() == "a"
    (tmp_path / "file").write_text("mine")
    with pytest.raises(RfcError, match="exists and is not a directory"):
        replace_directory(tmp_path / "file", "file", _writer({"a.vhd": "a"}))


def test_kept_files_replace_the_last_runs_and_a_users_directory_is_refused_first(tmp_path):
    keep = tmp_path / "keep"
    with kept_in(keep, "rfc msg loopback") as scratch:
        (scratch / "run.log").write_text("first")

    def failing_run() -> None:
        with kept_in(keep, "rfc msg loopback") as scratch:
            (scratch / "run.log").write_text("failed run")
            raise RuntimeError  # the work failed: its files are kept all the same

    with pytest.raises(RuntimeError):
        failing_run()
    assert _tree(keep)["run.log"] == "failed run"
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(RfcError, match="did not write"), kept_in(mine, "rfc msg loopback"):
        pytest.fail("the work must not start")
    assert _tree(mine) == {"notes.txt": "mine"}
