"""Verilator models: its run-time library compiled once a machine, models kept by content."""

from __future__ import annotations

import os
import subprocess

from rfc.toolchain.verilator import _ccache, run_testbench


def counting_bench(folder, limit):
    """A testbench that counts to `limit` and prints it: a distinct model per `limit`."""
    path = folder / f"count_{limit}.v"
    path.write_text(
        "module bench;\ninteger n;\ninitial begin\n"
        f"for (n = 0; n < {limit}; n = n + 1) ;\n"
        '$display("count=%0d", n);\n$finish;\nend\nendmodule\n'
    )
    return path


def cache_hits(directory) -> int:
    """How many compilations ccache has answered from `directory` so far."""
    printed = subprocess.run(
        [str(_ccache()), "--print-stats"],
        capture_output=True,
        text=True,
        check=True,
        env={"CCACHE_DIR": str(directory)},
    ).stdout
    counters = dict(line.split("\t") for line in printed.splitlines())
    return int(counters["direct_cache_hit"]) + int(counters["preprocessed_cache_hit"])


def test_a_second_model_takes_verilators_run_time_library_from_the_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("CCACHE_DIR", raising=False)
    first = run_testbench([counting_bench(tmp_path, 3)], "bench", {}, {}, tmp_path / "one")
    hits = cache_hits(tmp_path / "cache" / "ccache")
    second = run_testbench([counting_bench(tmp_path, 5)], "bench", {}, {}, tmp_path / "two")
    assert "count=3" in first
    assert "count=5" in second
    # verilated.cpp and verilated_threads.cpp, built in another scratch folder the second
    # time, come from the cache; the model itself is compiled
    assert cache_hits(tmp_path / "cache" / "ccache") - hits == 2


def test_a_model_built_on_every_core_is_reused_by_a_process_on_one(tmp_path, monkeypatch):
    # the build compiles on every core it may use; how many is not part of the model's key
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    bench = counting_bench(tmp_path, 4)
    assert "count=4" in run_testbench([bench], "bench", {}, {}, tmp_path / "one")
    (model,) = (tmp_path / "cache" / "verilator").iterdir()
    built = (model / "Vbench").stat().st_mtime_ns
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0})
    assert "count=4" in run_testbench([bench], "bench", {}, {}, tmp_path / "two")
    assert [entry.name for entry in (tmp_path / "cache" / "verilator").iterdir()] == [model.name]
    assert (model / "Vbench").stat().st_mtime_ns == built
