"""`rfc wizard` in a real pseudo-terminal: keystrokes in, a spec out that builds and simulates."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pexpect
import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
QUATERNION_EXAMPLE = ROOT / "examples" / "quaternion_to_euler"
PROMPT = r"(\]|\)|[a-z]): $"

# The answers that rebuild the paper's Listing 1 (examples/quaternion_to_euler/project.yaml),
# keyed by a piece of each question; questions not listed take their default (Enter).
LISTING_1 = {
    "Project name": "QuaternionToEuler",
    "Subscriber name": "orientation_sub",
    "Message type": "",  # subscriber and publisher, answered in order below
    "Topic": "",
    "Accelerator type name": "QuaternionToEuler",
    "Kind": "MyHDL",
    "Input ports": "q:geometry_msgs/Quaternion",
    "Output ports": "euler:geometry_msgs/Point",
    "Source file": "./accelerator.py",
    "Top": "quaternion_to_euler",
    "Python reference": "./accelerator.py:quaternion_to_euler_message",
    "Block name": "quat_to_euler",
    "Publisher name": "euler_pub",
}
IN_ORDER = {
    # Tab completes from the type store: the common prefix of Quaternion and QuaternionStamped
    "Message type": ["geometry_msgs/Quatern\t", "geometry_msgs/Point"],
    "Topic": ["/imu/orientation", "/imu/euler"],
}


def drive(directory: Path, answer, *args: str) -> str:
    """Run the wizard in a pty; `answer(question)` gives the keystrokes of each question."""
    child = pexpect.spawn(
        sys.executable,
        ["-m", "rfc", "wizard", *args],
        cwd=str(directory),
        encoding="utf-8",
        timeout=60,
        dimensions=(50, 200),
    )
    transcript = []
    while child.expect([PROMPT, pexpect.EOF]) == 0:
        shown = (child.before + child.after).replace("\r", "")
        transcript.append(shown)
        child.sendline(answer(shown.splitlines()[-1]))
    child.close()
    text = "".join(transcript) + child.before
    assert child.exitstatus == 0, text
    return text


def listing_1_answers(question: str) -> str:
    for key, value in LISTING_1.items():
        if key in question:
            return IN_ORDER[key].pop(0) if key in IN_ORDER else value
    return ""


def model_of(spec: Path, out: Path) -> str:
    result = run_rfc("build", spec, "--emit-ir", "--no-hardware", "-o", out)
    assert result.returncode == 0, result.stderr
    return (out / "model.yaml").read_text()


def test_enter_at_every_prompt_gives_a_starter_system_that_builds_and_simulates(tmp_path):
    transcript = drive(tmp_path, lambda question: "")
    assert "Tab completes" in transcript
    spec = tmp_path / "project.yaml"
    assert "type: ROS-SW" in spec.read_text()
    assert (tmp_path / "pass_through.py").exists()
    assert run_rfc("check", spec).returncode == 0
    build = run_rfc("build", spec, "-o", tmp_path / "build")
    assert build.returncode == 0, build.stderr
    types = message_types("ros2")
    points = [types.build("geometry_msgs/msg/Point", {"x": i, "y": -i, "z": 0.5}) for i in range(3)]
    frames = [types.serialize(p, "geometry_msgs/msg/Point") for p in points]
    bag_in, bag_out = tmp_path / "in.mcap", tmp_path / "out.mcap"
    write_bag(
        bag_in,
        types,
        {"/input": "geometry_msgs/msg/Point"},
        [("/input", 1000 * (i + 1), f) for i, f in enumerate(frames)],
    )
    sim = run_rfc("sim", spec, "--bag", bag_in, "--out", bag_out, "--json", cwd=tmp_path)
    assert sim.returncode == 0, sim.stderr
    assert json.loads(sim.stdout)["published"] == {"/output": 3}
    assert [m.data for m in read_bag(bag_out, types)] == frames


def test_the_wizard_rebuilds_listing_1_with_the_examples_holistic_model(tmp_path):
    for name in (
        "accelerator.py",
        "quat_to_euler.py",
        "quat_to_euler_pipelined.py",
        "split_accumulator.py",
        "compare.py",
        "make_bags.py",
    ):
        shutil.copy(QUATERNION_EXAMPLE / name, tmp_path / name)
    transcript = drive(tmp_path, listing_1_answers, "-o", "listing1.yaml")
    assert "geometry_msgs/msg/Quaternion\n  x: float64\n  y: float64" in transcript
    spec = tmp_path / "listing1.yaml"
    assert model_of(spec, tmp_path / "a") == model_of(
        QUATERNION_EXAMPLE / "project.yaml", tmp_path / "b"
    )
    bag_in, bag_out = tmp_path / "q.mcap", tmp_path / "euler.mcap"
    made = pexpect.run(
        f"{sys.executable} make_bags.py random 4 {bag_in}", cwd=str(tmp_path), withexitstatus=True
    )
    assert made[1] == 0, made[0]
    sim = run_rfc("sim", spec, "--bag", bag_in, "--out", bag_out, cwd=tmp_path)
    assert sim.returncode == 0, sim.stderr
    compared = pexpect.run(
        f"{sys.executable} compare.py {bag_in} {bag_out}", cwd=str(tmp_path), withexitstatus=True
    )
    assert compared[1] == 0, compared[0]


def test_the_python_and_yaml_forms_of_the_same_answers_give_the_same_model(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text("Replayed\n" + "\n" * 9 + "x, y\n\n5 us\n")  # fields x, y; a period
    models = []
    for form in ("py", "yaml"):
        (tmp_path / form).mkdir()
        spec = f"{form}/project.{form}"
        result = run_rfc("wizard", "-o", spec, "--answers", answers, cwd=tmp_path)
        assert result.returncode == 0, result.stderr
        assert "Project name [Starter]: Replayed" in result.stdout
        models.append(model_of(tmp_path / spec, tmp_path / form / "build"))
    assert models[0] == models[1]
    assert "include:\n      - x\n      - y" in models[0]


def test_a_wrong_replayed_answer_names_its_line_and_writes_nothing(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text("\n" * 9 + "geometry_msgs/Quaternoin\n")
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 1
    assert f"{answers}:10:1: unknown message type 'geometry_msgs/Quaternoin'" in result.stderr
    assert "did you mean 'geometry_msgs/Quaternion'" in result.stderr
    assert "Traceback" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["answers.txt"]


def test_a_myhdl_accelerator_without_source_gets_rfc_stubs_skeleton_and_builds(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text("\n" * 14 + "Scale\nMyHDL\n")
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "./scale.py does not exist yet; write a skeleton there? (y/n) [y]: " in result.stdout
    skeleton = (tmp_path / "scale.py").read_text()
    shown = run_rfc("stub", tmp_path / "project.yaml", "Scale", "--lang", "myhdl")
    assert skeleton == shown.stdout
    build = run_rfc("build", tmp_path / "project.yaml", "-o", tmp_path / "build")
    assert build.returncode == 0, build.stderr


def test_an_hls_accelerator_without_source_gets_rfc_stubs_skeleton_and_checks(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text("\n" * 14 + "Scale\nHLS\n")
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "./scale.cpp does not exist yet; write a skeleton there? (y/n) [y]: " in result.stdout
    skeleton = (tmp_path / "scale.cpp").read_text()
    shown = run_rfc("stub", tmp_path / "project.yaml", "Scale", "--lang", "hls")
    assert skeleton == shown.stdout
    assert "void Scale(" in skeleton
    assert run_rfc("check", tmp_path / "project.yaml").returncode == 0


def test_with_periods_the_wizard_offers_the_dse_recommendation(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text("\n" * 14 + "Scale\nMyHDL\n" + "\n" * 11 + "10 us\n")
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    # one publisher in the logic: resolve-scheduler's rule (every algorithm serves it alike)
    assert "rfc dse recommends PFP: one publisher" in result.stdout
    assert "[PFP]: " in result.stdout
    assert "scheduler: PFP" in (tmp_path / "project.yaml").read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["answers.txt", "project.yaml", "scale.py"]


def test_an_existing_spec_is_never_overwritten(tmp_path):
    (tmp_path / "project.yaml").write_text("mine\n")
    result = run_rfc("wizard", cwd=tmp_path)
    assert result.returncode == 1
    assert "'project.yaml' already exists" in result.stderr
    assert (tmp_path / "project.yaml").read_text() == "mine\n"
    missing = run_rfc("wizard", "-o", "new/project.yaml", cwd=tmp_path)
    assert missing.returncode == 1
    assert "the folder of 'new/project.yaml' does not exist" in missing.stderr


def test_closed_input_takes_the_defaults(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "rfc", "wizard"],
        cwd=tmp_path,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert run_rfc("check", tmp_path / "project.yaml").returncode == 0


@pytest.mark.slow  # 15 s, 90 s while the schedulers' synthesis cache is cold
def test_two_publishers_with_periods_get_rfc_dses_ranking_as_the_default(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text(
        "\n" * 14
        + "Split\nMyHDL\n\na:geometry_msgs/Point, b:geometry_msgs/Point\n"
        + "\n" * 6
        + "\n\n\n2 us\ny\n\n\n\n4 us\n"
    )
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    ranked = run_rfc("dse", tmp_path / "project.yaml", "--json")
    assert ranked.returncode == 0, ranked.stderr
    recommended = json.loads(ranked.stdout)["recommended"]
    assert f"rfc dse recommends {recommended}: " in result.stdout
    assert f"scheduler: {recommended}\n" in (tmp_path / "project.yaml").read_text()


def test_a_system_that_does_not_check_is_reported_at_the_specs_line_and_nothing_stays(tmp_path):
    answers = tmp_path / "answers.txt"
    answers.write_text("\n" * 14 + "Scale\nMyHDL\n" + "\n" * 13 + "input_sub>output_pub\n")
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 1
    assert re.search(r"error: project\.yaml:\d+:\d+: ", result.stderr), result.stderr
    assert ".rfc-wizard-draft" not in result.stderr
    assert "Traceback" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["answers.txt"]


@pytest.mark.parametrize(
    ("line", "answer", "message", "hint"),
    [
        (7, "no_msgs", "'no_msgs' is not a directory", "give folders that hold <package>/msg/"),
        (8, "missing.bag", "bag 'missing.bag' does not exist", None),
    ],
)
def test_a_path_that_does_not_exist_names_its_answer_and_writes_nothing(
    tmp_path, line, answer, message, hint
):
    answers = tmp_path / "answers.txt"
    answers.write_text("\n" * (line - 1) + f"{answer}\n")
    result = run_rfc("wizard", "--answers", answers, cwd=tmp_path)
    assert result.returncode == 1
    first = result.stderr.splitlines()[0]
    assert first == f"error: {answers}:{line}:1: {message} (paths are relative to .)"
    assert (hint in result.stderr) if hint else ("hint" not in result.stderr)
    assert "Traceback" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["answers.txt"]
