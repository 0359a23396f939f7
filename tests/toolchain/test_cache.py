"""Compiled simulators are kept small and few: a build's intermediates go, old entries go."""

from __future__ import annotations

import os
import time

import pytest

from rfc.toolchain.cache import (
    ABANDONED_SECONDS,
    prune,
    publish_build,
    scratch_build,
    used,
)


def fake_build(folder, program="Vtop"):
    """What a Verilator build leaves: a program, precompiled headers, objects, sources."""
    (folder / program).write_bytes(b"\x7fELF program")
    for name in ("Vtop__pch.h.fast.gch", "Vtop.o", "Vtop__ALL.a", "Vtop.d", "Vtop.cpp"):
        (folder / name).write_bytes(b"x" * 1000)


def test_a_published_build_keeps_its_program_and_drops_its_intermediates(tmp_path):
    entry = tmp_path / "models" / "abc"
    with scratch_build(entry) as partial:
        fake_build(partial)
        assert publish_build(partial, entry) == entry
    assert sorted(p.name for p in entry.iterdir()) == ["Vtop", "Vtop.cpp"]
    assert [p.name for p in entry.parent.iterdir()] == ["abc"]  # no scratch folder left


def test_a_failed_build_leaves_nothing(tmp_path):
    entry = tmp_path / "models" / "abc"

    def build() -> None:
        with scratch_build(entry) as partial:
            fake_build(partial)
            raise RuntimeError("the compiler failed")

    with pytest.raises(RuntimeError, match="compiler failed"):
        build()
    assert list(entry.parent.iterdir()) == []


def test_when_another_build_published_first_its_entry_stays(tmp_path):
    entry = tmp_path / "models" / "abc"
    with scratch_build(entry) as first, scratch_build(entry) as second:
        fake_build(first, program="first")
        fake_build(second, program="second")
        publish_build(first, entry)
        publish_build(second, entry)
    assert (entry / "first").is_file()
    assert not (entry / "second").exists()
    assert [p.name for p in entry.parent.iterdir()] == ["abc"]


def aged(path, seconds):
    past = time.time() - seconds
    os.utime(path, (past, past))
    return path


def test_pruning_keeps_the_entries_used_last(tmp_path):
    entries = [tmp_path / f"model{i}" for i in range(5)]  # model4 built last
    for age, entry in enumerate(reversed(entries)):
        entry.mkdir()
        aged(entry, 1000 * (age + 1))
    used(entries[0])  # the oldest, used again just now
    prune(tmp_path, kept=2)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model0", "model4"]


def test_pruning_removes_scratch_folders_a_dead_build_left_only(tmp_path):
    (tmp_path / "model").mkdir()
    abandoned = tmp_path / "model.x1y2"
    running = tmp_path / "model.a3b4"
    abandoned.mkdir()
    running.mkdir()
    aged(abandoned, ABANDONED_SECONDS + 60)
    prune(tmp_path, kept=8)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model", "model.a3b4"]
