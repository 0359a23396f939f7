"""`rfc dse`: the sweep's JSON, files and --verify-hdl; a project's recommendation; errors.

Each test runs the real command line once or twice: the sweep's files and JSON are checked on
one run of the issue's command, so that parallel test workers never repeat it.
"""

from __future__ import annotations

import csv
import json
import shutil
import sys
from pathlib import Path

import pexpect
import pytest

from rfc.dse.kernel import METRICS
from rfc.dse.plots import FIGURES
from rfc.dse.sweep import ALGORITHMS, COMBINATIONS
from tests.support.cli import run_rfc
from tests.support.dask_cluster import dask_scheduler  # noqa: F401 (a fixture)

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
HUB = EXAMPLES / "sensor_hub" / "SensorHub.yaml"
MULTI_TYPE = EXAMPLES / "multi_type" / "MultiType.yaml"

#: A spec whose only accelerator runs in software: the logic has no publisher to schedule.
SOFTWARE_ONLY = """\
project: {name: SoftwareOnly, middleware: ROS2}
accelerators:
  - name: PassTwist
    type: ROS-SW
    sources: ./passthrough.py
    reference: identity
    interface:
      input: [{message: geometry_msgs/Twist}]
      output: [{message: geometry_msgs/Twist}]
blocks:
  - {name: Twist_sub, type: ROS>accelerator, message: geometry_msgs/Twist, topic: /in,
     outgoing: [{name: Pass_acc}]}
  - {name: Pass_acc, type: PassTwist, outgoing: [{name: Twist_pub}]}
  - {name: Twist_pub, type: accelerator>ROS, message: geometry_msgs/Twist, topic: /out}
"""


@pytest.mark.slow
def test_the_issue_command_prints_all_six_and_writes_figures_and_report(tmp_path):
    out = tmp_path / "OUT"
    result = run_rfc(
        "dse", "--n", "8,16", "--dataset", "large", "--replicates", "4", "-o", out, "--json"
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    points = {(p["scheduler"], p["n"]): p for p in report["points"]}
    expected = {(a, n) for a in ALGORITHMS for n in (8, 16)} | {(c, 16) for c in COMBINATIONS}
    assert set(points) == expected
    for point in points.values():
        assert (point["dataset"], point["replicates"], point["cycles"]) == ("large", 4, 10_000)
        assert set(point["metrics"]) == set(METRICS)
        for summary in point["metrics"].values():
            if summary["mean"] is not None:
                assert summary["low"] <= summary["mean"] <= summary["high"]
    assert {(r["algorithm"], r["n"]) for r in report["resources"]} == {
        (a, n) for a in ALGORITHMS for n in (8, 16)
    }
    assert all(r["lut"] > 0 and r["ff"] > 0 for r in report["resources"])
    assert [row["n"] for row in report["table3"]] == [8, 16]
    assert report["output"] == str(out)
    # paper §7.2.2: fixed priority completes few; the dynamic schedulers complete all 16
    assert points["NPFP", 16]["metrics"]["completed"]["mean"] < 8
    assert points["LOEDF", 16]["metrics"]["completed"]["mean"] == 16

    assert json.loads((out / "results.json").read_text())["points"] == report["points"]
    for name in FIGURES:
        assert (out / f"{name}.png").read_bytes().startswith(b"\x89PNG")
        assert "<svg" in (out / f"{name}.svg").read_text()
    page = (out / "report.html").read_text()
    assert all(f"src='{name}.svg'" in page for name in FIGURES)
    with (out / "results.csv").open() as rows:
        assert len(list(csv.DictReader(rows))) == len(report["points"]) * len(METRICS)
    with (out / "resources.csv").open() as rows:
        assert len(list(csv.DictReader(rows))) == len(report["resources"])
    assert (out / "table3.md").read_text().startswith("# Table 3")


@pytest.mark.slow
def test_verify_hdl_passes_on_the_sampled_points_and_a_rerun_replaces_its_files(tmp_path):
    out = tmp_path / "out"
    args = ("dse", "--n", "2,4", "--dataset", "large", "--replicates", "2", "--no-synth", "-o", out)
    result = run_rfc(*args, "--verify-hdl")
    assert result.returncode == 0, result.stderr
    assert "--verify-hdl: 6 points equal in GHDL" in result.stderr
    assert "dataset large" in result.stdout
    assert all(name in result.stdout for name in ALGORITHMS)
    checks = json.loads((out / "verify.json").read_text())
    assert [c["scheduler"] for c in checks] == list(ALGORITHMS)
    for check in checks:
        assert (check["n"], check["cycles"], check["error"]) == (2, 10_000, None)
        assert check["equal"]
        assert check["dse"] == check["ghdl"]
        assert check["ghdl"]["messages"] > 0
    assert not (out / "resources.csv").exists()

    again = run_rfc(*args, "--jobs", "1", "--json")
    assert again.returncode == 0, again.stderr
    assert "verify_hdl" not in json.loads(again.stdout)
    assert not (out / "verify.json").exists()
    assert (out / "report.html").exists()


@pytest.mark.parametrize("sizes", [("--n", "2"), ("--n", "2,4", "--no-figures")])
def test_without_figures_the_sweep_writes_its_tables_and_a_report_without_images(tmp_path, sizes):
    out = tmp_path / "out"
    result = run_rfc("dse", *sizes, "--dataset", "cc1", "--replicates", "2", "--no-synth",
                     "-o", out)  # fmt: skip
    assert result.returncode == 0, result.stderr
    written = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert written == ["report.html", "results.csv", "results.json"]
    page = (out / "report.html").read_text()
    assert "<img" not in page
    assert "<h2>Dataset cc1</h2>" in page
    assert f"wrote tables and report.html into {out}" in result.stderr


@pytest.mark.slow
def test_a_cold_first_run_says_it_compiles_the_kernels_and_the_next_run_loads_them(tmp_path):
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    args = ("dse", "--n", "4", "--dataset", "cc1", "--replicates", "2", "--no-synth", "--json")
    cold = run_rfc(*args, "-o", tmp_path / "cold", env=env)
    warm = run_rfc(*args, "-o", tmp_path / "warm", env=env)
    assert cold.returncode == warm.returncode == 0, cold.stderr + warm.stderr
    assert "compiling the DSE kernels with numba" in cold.stderr
    assert "compiling" not in warm.stderr
    assert any((tmp_path / "numba").rglob("*.nbi"))
    documents = [json.loads(run.stdout) for run in (cold, warm)]
    assert documents[0]["points"] == documents[1]["points"]


def test_a_directory_rfc_did_not_write_is_kept(tmp_path):
    (tmp_path / "mine.txt").write_text("keep me")
    result = run_rfc("dse", "--n", "2", "--dataset", "cc1", "--replicates", "2", "--no-synth",
                     "-o", tmp_path)  # fmt: skip
    assert result.returncode == 1
    assert "holds files that rfc dse did not write" in result.stderr
    assert (tmp_path / "mine.txt").read_text() == "keep me"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--n", "1,8"), "--n '1,8': each N must be between 2 and 1024"),
        (("--n", "eight"), "--n 'eight' is not a comma-separated list of integers"),
        (("--dataset", "cc9"), "unknown dataset 'cc9'"),
        (("--objective", "lut"), "--objective ranks a project's schedulers; give the project's"),
        (("--objective", "fastest", HUB), "unknown objective criterion 'fastest'"),
        (("--n", "8", "--verify-hdl", HUB), "--n, --verify-hdl apply to the paper's sweep"),
        (("--figures", HUB), "--figures applies to the paper's sweep"),
        ((MULTI_TYPE,), "publishers Image_pub, Scan_pub, Twist_pub of project 'MultiType' have"),
        (("missing.yaml",), "spec 'missing.yaml' does not exist"),
    ],
)
def test_bad_input_is_one_clear_error(args, message, tmp_path):
    result = run_rfc("dse", *args, "-o", tmp_path / "out")
    assert result.returncode == 1, result.stderr
    assert message in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "out").exists()


def test_a_spec_without_publishers_in_the_logic(tmp_path):
    passthrough = (EXAMPLES / "multi_type" / "passthrough.py").read_text()
    (tmp_path / "passthrough.py").write_text(passthrough)
    (tmp_path / "SoftwareOnly.yaml").write_text(SOFTWARE_ONLY)
    result = run_rfc("dse", tmp_path / "SoftwareOnly.yaml")
    assert result.returncode == 1
    assert "project 'SoftwareOnly' has no publisher in the logic to schedule" in result.stderr
    assert "Traceback" not in result.stderr


def test_project_recommendation_with_reasons(tmp_path):
    result = run_rfc("dse", HUB, "-o", tmp_path / "rec")
    assert result.returncode == 0, result.stderr
    assert "SensorHub: 6 publishers, 10000 cycles simulated" in result.stdout
    assert "recommended: LOEDF" in result.stdout
    assert "LUTs: " in result.stdout
    assert "this decides" in result.stdout
    document = json.loads((tmp_path / "rec" / "recommendation.json").read_text())
    assert document["recommended"] == "LOEDF"
    assert document["objective"] == ["completed", "missed", "max_lateness", "lut"]
    assert document["ranking"][0]["lut"] < document["ranking"][1]["lut"]
    assert len(document["ranking"]) == 10
    custom = run_rfc("dse", HUB, "--json", "--objective", "completed,response")
    assert custom.returncode == 0, custom.stderr
    ranking = json.loads(custom.stdout)["ranking"]
    responses = [c["metrics"]["response"] for c in ranking if c["metrics"]["completed"] == 6]
    assert responses == sorted(responses)


def test_a_spec_whose_accelerator_is_still_a_stub_gets_a_recommendation(tmp_path):
    # the schedulers see only the publishers' traffic; `rfc check` refuses the empty function
    shutil.copy(HUB, tmp_path / HUB.name)
    (tmp_path / "state_estimator.cpp").write_text("void StateEstimator() {}\n")
    result = run_rfc("dse", tmp_path / HUB.name, "--horizon", "2000", "--json")
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["recommended"]
    checked = run_rfc("check", tmp_path / HUB.name)
    assert checked.returncode == 1
    assert "HLS top function StateEstimator of accelerator 'StateEstimator' has 0" in (
        checked.stderr
    )


def test_build_uses_the_recommendation(tmp_path):
    result = run_rfc("build", HUB, "-o", tmp_path / "build", "--no-hardware")
    assert result.returncode == 0, result.stderr
    report = (tmp_path / "build" / "report.md").read_text()
    assert "## Scheduler: LOEDF" in report
    assert "Chosen by resolve-scheduler: rfc dse:" in report


def test_dse_spec_horizon_sets_the_cycles_simulated():
    result = run_rfc(
        "dse", EXAMPLES / "sensor_hub" / "SensorHub.yaml", "--horizon", "20000", "--json"
    )
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["cycles"] == 20_000
    assert [p["messages"] for p in document["publishers"]] == [
        -(-20_000 // p["period"]) for p in document["publishers"]
    ]


def test_dse_horizon_without_spec_is_refused():
    result = run_rfc("dse", "--horizon", "20000", "--n", "2")
    assert result.returncode == 1
    assert "--horizon sets how long a project is simulated" in result.stderr


@pytest.mark.parametrize("as_json", [True, False])
def test_dse_spec_shows_progress_at_a_terminal_unless_json(as_json):
    hub = EXAMPLES / "sensor_hub" / "SensorHub.yaml"
    args = ["-m", "rfc", "dse", str(hub), "--horizon", "2000", *(["--json"] if as_json else [])]
    output, status = pexpect.run(
        sys.executable, args=args, withexitstatus=True, encoding="utf-8", timeout=300
    )
    assert status == 0, output
    if as_json:
        assert json.loads(output)["cycles"] == 2000  # nothing but the document on the terminal
    else:
        assert "simulating candidates" in output


def test_a_sweep_on_a_dask_cluster_gives_the_serial_document(tmp_path, dask_scheduler):  # noqa: F811
    args = ("dse", "--n", "4", "--dataset", "cc2", "--replicates", "3", "--no-synth", "--json")
    serial = run_rfc(*args, "--jobs", "1", "-o", tmp_path / "serial")
    clustered = run_rfc(*args, "--cluster", dask_scheduler, "-o", tmp_path / "cluster")
    assert clustered.returncode == 0, clustered.stderr
    documents = [json.loads(r.stdout) for r in (serial, clustered)]
    for document in documents:
        del document["output"]
    assert documents[0] == documents[1]
    assert (tmp_path / "cluster" / "results.csv").read_bytes() == (
        tmp_path / "serial" / "results.csv"
    ).read_bytes()
