"""Ctrl-C during `rfc sim`: rfc stops, the simulator and every other child with it, no traceback.

The simulator is GHDL (under cocotb) or the Verilated logic with its C++ testbench (``Vdut``).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rfc.cli.interrupt import INTERRUPTED_STATUS, descendants
from rfc.messages.rosbags_adapter import message_types, write_bag
from tests.runtime.support import pose_messages, system_copy

ROOT = Path(__file__).resolve().parents[2]
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"


def _name(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/comm").read_text().strip()
    except OSError:
        return ""


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


#: Each simulator and the name of its process.
SIMULATORS = {"ghdl": "ghdl", "verilator": "Vdut"}


@pytest.mark.parametrize("simulator", SIMULATORS)
def test_sigint_stops_rfc_sim_and_the_simulator(tmp_path, simulator):
    types = message_types("ros2")
    bag = tmp_path / "in.mcap"
    rows = [(m.topic, m.timestamp_ns, m.data) for m in pose_messages(types, 3000)]
    write_bag(bag, types, {"/amcl_pose": POSE}, rows)
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    out = tmp_path / "out.mcap"
    command = [sys.executable, "-m", "rfc", "sim", spec, "--bag", bag, "--out", out,
               "--simulator", simulator]  # fmt: skip
    process = subprocess.Popen(
        list(map(str, command)),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        start_new_session=True,  # its own group: the signal goes to rfc alone, not to pytest
    )
    try:
        simulators: list[int] = []
        deadline = time.monotonic() + 300  # Verilator compiles the logic first
        while not simulators and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.2)
            found = descendants(process.pid)
            simulators = [p for p in found if SIMULATORS[simulator] in _name(p)]
        assert simulators, "the simulator never started"
        time.sleep(1)  # well inside the simulation
        os.kill(process.pid, signal.SIGINT)
        _, stderr = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    assert process.returncode == INTERRUPTED_STATUS, stderr
    assert "interrupted: stopped rfc and every process it started" in stderr
    assert "Traceback" not in stderr
    time.sleep(0.5)
    assert not [pid for pid in simulators if _alive(pid)]
    assert not out.exists()
