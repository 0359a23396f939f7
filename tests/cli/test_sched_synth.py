"""`rfc sched synth`: the JSON contract (docs/architecture.md), caching, and user errors."""

from __future__ import annotations

import json

import pytest

from tests.support.cli import run_rfc
from tests.support.dask_cluster import dask_scheduler  # noqa: F401 (a fixture)


@pytest.fixture(scope="module")
def module_cache(tmp_path_factory):
    return tmp_path_factory.mktemp("synthesis-cache")


@pytest.fixture(autouse=True)
def private_cache(module_cache, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(module_cache))


def synth_json(*args):
    result = run_rfc("sched", "synth", *args, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_json_has_the_contract_keys():
    report = synth_json("--algorithm", "npfp", "--n", "4")
    assert {"algorithm", "n", "lut", "ff", "grant_latency_cycles"} <= set(report)
    assert report["algorithm"] == "NPFP"
    assert report["n"] == 4
    assert report["lut"] > 0
    assert report["ff"] > 0
    assert report["grant_latency_cycles"] == 1


def test_json_has_the_critical_path_and_the_fmax_it_allows():
    small = synth_json("--algorithm", "npfp", "--n", "2")
    large = synth_json("--algorithm", "npfp", "--n", "64")
    for report in (small, large):
        path = report["critical_path"]
        assert path["delay_ns"] > 0
        assert path["levels"] >= 1
        # routing is allowed as much time again as the cells
        assert report["fmax_mhz"] == pytest.approx(1000 / (2 * path["delay_ns"]), rel=1e-3)
    # a priority encoder over 64 requests is deeper than over 2
    assert large["critical_path"]["delay_ns"] > small["critical_path"]["delay_ns"]
    assert large["fmax_mhz"] < small["fmax_mhz"]


def test_a_second_run_comes_from_the_cache_with_the_same_figures(tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "fresh-cache"))
    first = synth_json("-a", "PFP", "-n", "3", "-o", str(tmp_path / "hdl"))
    second = synth_json("-a", "PFP", "-n", "3")
    assert (first["cached"], second["cached"]) == (False, True)
    assert (first["lut"], first["ff"]) == (second["lut"], second["ff"])
    assert first["critical_path"] == second["critical_path"]
    assert (tmp_path / "hdl" / "rfc_sched_pfp3.vhd").is_file()
    assert (tmp_path / "hdl" / "rfc_sched_pfp3.v").is_file()


def test_a_composition_is_a_scheduler_too():
    report = synth_json("-a", "LRU(PFP,ROEDF:2)", "-n", "5")
    assert report["algorithm"] == "LRU(PFP3,ROEDF2)"
    assert report["lut"] > 0
    # ROEDF (2) then LRU (1) for a request of the last input.
    assert report["grant_latency_cycles"] == 3


def test_table_output_names_the_figures():
    result = run_rfc("sched", "synth", "-a", "NPFP", "-n", "4")
    assert result.returncode == 0, result.stderr
    assert "LUTs" in result.stdout
    assert "grant latency" in result.stdout
    assert "Fmax estimate" in result.stdout


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("-a", "LOEFD", "-n", "4"), "did you mean 'LOEDF'"),
        (("-a", "LST", "-n", "0"), "between 1 and 1024 inputs, not 0"),
        (("-a", "LST", "-n", "4", "--deadline", "0"), "at least 1 cycle"),
        (("-a", "LRU(LST:1,LST:1)", "-n", "4"), "must share the 4 inputs"),
        (("-a", "LOEDF", "-n", "2", "--counter-bits", "0"), "counter width 0 bits cannot hold"),
        (("-a", "LST", "-n", "2", "--counter-bits", "-3"), "it must be from 1 to 48"),
    ],
)
def test_bad_input_is_one_message_and_exit_1(args, message):
    result = run_rfc("sched", "synth", *args, "--json")
    assert result.returncode == 1
    assert message in result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout == ""


def test_missing_options_are_bad_usage():
    assert run_rfc("sched", "synth", "-a", "LRU").returncode == 2


def test_output_that_is_a_file_or_a_users_directory_is_refused_before_synthesis(tmp_path):
    (tmp_path / "file.txt").write_text("mine")
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("mine")
    for output, message in (
        ("file.txt", "output 'file.txt' exists and is not a directory"),
        ("mine", "output directory 'mine' holds files that rfc sched synth did not write"),
    ):
        result = run_rfc("sched", "synth", "-a", "LRU", "-n", "2", "-o", output, cwd=tmp_path)
        assert result.returncode == 1
        assert message in result.stderr
        assert "Traceback" not in result.stderr
    assert (tmp_path / "file.txt").read_text() == "mine"
    assert [p.name for p in (tmp_path / "mine").iterdir()] == ["notes.txt"]


def test_a_list_of_n_on_a_dask_cluster_gives_the_serial_reports(dask_scheduler):  # noqa: F811
    args = ("sched", "synth", "-a", "NPFP", "--n", "3,2", "--no-cache", "--json")
    serial = run_rfc(*args)
    clustered = run_rfc(*args, "--cluster", dask_scheduler)
    assert clustered.returncode == 0, clustered.stderr
    reports = json.loads(clustered.stdout)
    assert reports == json.loads(serial.stdout)
    assert [r["n"] for r in reports] == [2, 3]
    assert reports[0] == synth_json("-a", "NPFP", "--n", "2", "--no-cache")


def test_output_with_a_list_of_n_is_refused(tmp_path):
    result = run_rfc("sched", "synth", "-a", "LRU", "--n", "2,4", "-o", tmp_path / "hdl")
    assert result.returncode == 1
    assert "--output writes one scheduler's VHDL and Verilog; --n gives several" in result.stderr
    assert not (tmp_path / "hdl").exists()
