"""User code cannot hang rfc nor end it silently: a time limit, and sys.exit as an error."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rfc import user_code
from rfc.errors import RfcError
from rfc.messages.rosbags_adapter import message_types, write_bag
from rfc.user_code import TIME_LIMIT_ENV, running_user_code
from tests.runtime.support import pose_messages, system_copy

ROOT = Path(__file__).resolve().parents[1]
LISTING_1_PY = ROOT / "examples" / "rotation_converter" / "RotationConverterNode.py"
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"


def rfc(*args: object, limit: str = "1") -> subprocess.CompletedProcess[str]:
    """The real command line with a 1 s limit on user code; it must end well within 60 s."""
    started = time.monotonic()
    result = subprocess.run(
        [sys.executable, "-m", "rfc", *map(str, args)],
        capture_output=True,
        text=True,
        env={**os.environ, TIME_LIMIT_ENV: limit},
        timeout=60,
        check=False,
    )
    assert time.monotonic() - started < 60
    assert "Traceback" not in result.stderr
    return result


def test_an_endless_loop_in_a_python_spec_is_an_error_naming_it(tmp_path):
    spec = tmp_path / "spec.py"
    spec.write_text(
        LISTING_1_PY.read_text().replace("import rfc", "import rfc\nwhile True:\n    pass")
    )
    result = rfc("check", spec)
    assert result.returncode == 1
    assert f"error: the Python spec '{spec}' did not finish within 1 s" in result.stderr
    assert f"set {TIME_LIMIT_ENV}=SECONDS" in result.stderr


def test_a_loop_that_catches_every_exception_still_ends(tmp_path):
    spec = tmp_path / "spec.py"
    loop = "while True:\n    try:\n        pass\n    except Exception:\n        pass\n"
    spec.write_text(loop)
    result = rfc("build", spec, "-o", tmp_path / "out")
    assert result.returncode == 1
    assert "did not finish within 1 s" in result.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("code", ["0", "'bye'"])
def test_sys_exit_in_a_spec_is_an_error_not_a_silent_exit(tmp_path, code):
    spec = tmp_path / "spec.py"
    spec.write_text(f"import sys\nsys.exit({code})\n")
    result = rfc("check", spec)
    assert result.returncode == 1
    assert f"the Python spec '{spec}' called sys.exit({code}); rfc stops" in result.stderr


def test_a_myhdl_source_that_never_finishes_importing_is_an_error(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    source = tmp_path / "passthrough.py"
    source.write_text("import time\ntime.sleep(3600)\n" + source.read_text())
    result = rfc("build", spec, "-o", tmp_path / "out")
    assert result.returncode == 1
    assert (
        "importing 'passthrough.py' for accelerator 'PassPose' did not finish within 1 s"
        in result.stderr
    )


def test_a_ros_sw_function_that_never_returns_is_an_error_naming_it(tmp_path):
    spec = system_copy(tmp_path, "pose_mixed.yaml", ("type: MyHDL", "type: ROS-SW"))
    source = tmp_path / "passthrough.py"
    source.write_text(
        source.read_text().replace(
            "def clear_covariance(message):",
            "def clear_covariance(message):\n    while True:\n        pass",
        )
    )
    types = message_types("ros2")
    bag = tmp_path / "in.mcap"
    write_bag(
        bag,
        types,
        {"/amcl_pose": POSE},
        [(m.topic, m.timestamp_ns, m.data) for m in pose_messages(types, 2)],
    )
    out = tmp_path / "out.mcap"
    result = rfc("sim", spec, "--bag", bag, "--out", out)
    assert result.returncode == 1
    assert (
        "ROS-SW function 'clear_covariance' of accelerator 'Clear' (call 1) did not finish "
        "within 1 s" in result.stderr
    )
    assert not out.exists()


@pytest.mark.parametrize("value", ["0", "soon"])
def test_a_bad_time_limit_is_an_error(tmp_path, value):
    result = rfc("check", LISTING_1_PY, limit=value)
    assert result.returncode == 1
    assert f"{TIME_LIMIT_ENV}='{value}' is not a positive number of seconds" in result.stderr


def test_the_limit_is_lifted_after_the_code_ran(monkeypatch):
    monkeypatch.setenv(TIME_LIMIT_ENV, "0.2")
    with running_user_code("quick code"):
        pass
    time.sleep(0.4)  # no stray alarm goes off afterwards
    with (
        pytest.raises(RfcError, match=r"slow code did not finish within 0\.2 s"),
        running_user_code("slow code"),
    ):
        time.sleep(5)


def test_the_limit_counts_computing_and_stops_waiting_later(monkeypatch):
    monkeypatch.setenv(TIME_LIMIT_ENV, "0.2")
    monkeypatch.setattr(user_code, "WALL_FACTOR", 100.0)  # the CPU timer first, however busy
    with running_user_code("waiting code"):
        time.sleep(0.5)  # waiting is not computing
    with pytest.raises(RfcError, match=r"busy code did not finish within 0\.2 s\n"):
        spin("busy code")
    monkeypatch.setattr(user_code, "WALL_FACTOR", 5.0)
    waited = r"blocked code .* 0\.2 s \(1 s in all, most of it waiting\)"
    with pytest.raises(RfcError, match=waited), running_user_code("blocked code"):
        time.sleep(5)


def spin(what: str) -> None:
    """Compute forever under the limit."""
    with running_user_code(what):
        while True:
            pass
