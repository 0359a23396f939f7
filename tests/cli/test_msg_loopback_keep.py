"""`rfc msg loopback --keep DIR`: relative paths work, and a user's directory is never filled."""

from __future__ import annotations

from tests.conftest import shared_file
from tests.support.cli import run_rfc


def _loopback(keep, cwd):
    bag = shared_file("bags/cdr_test_0.mcap")
    args = ("msg", "loopback", "test_msgs/msg/BasicTypes", "--bag", bag, "--count", "2")
    return run_rfc(*args, "--keep", keep, cwd=cwd)


def test_a_relative_keep_directory_holds_the_run_and_is_replaced_next_time(tmp_path):
    first = _loopback("kept", tmp_path)
    assert first.returncode == 0, first.stderr
    assert (tmp_path / "kept" / "rfc_loopback.vhd").is_file()
    again = _loopback("kept", tmp_path)
    assert again.returncode == 0, again.stderr


def test_a_directory_of_the_users_is_refused_before_the_run(tmp_path):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("keep me")
    result = _loopback("mine", tmp_path)
    assert result.returncode == 1
    assert "'mine' holds files that rfc msg loopback did not write" in result.stderr
    assert "Traceback" not in result.stderr
    assert [p.name for p in (tmp_path / "mine").iterdir()] == ["notes.txt"]
