"""What a drop gate and a frame guard add in front of a subscriber, as report.md lists it."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from myhdl import _simulator as myhdl_simulator

from rfc.driver import compile_spec
from rfc.lower.system.latency import gate_latency, guard_latency, subscriber_latency
from rfc.messages.rosbags_adapter import message_types
from tests.cli.test_sim_malformed import JOINTS, MAXIMA, POINT, spec_text
from tests.lower.system.systems import PASS_THROUGH, write_spec
from tests.support.cli import run_rfc


def joint_state(count: int, ros1: bool) -> dict:
    """A JointState of `count` joints (names within the maxima), as rosbags builds it."""
    header = {"stamp": {"sec": 3, "nanosec": 7}, "frame_id": "base"}
    return {
        "header": {**header, "seq": 1} if ros1 else header,
        "name": ["j" * MAXIMA.string] * count,
        "position": np.arange(count, dtype=np.float64),
        "velocity": np.zeros(count),
        "effort": np.zeros(0),
    }


@pytest.mark.parametrize(("middleware", "width"), [("ROS2", 8), ("ROS1", 32), ("ROS2", 64)])
def test_a_frame_guard_delays_a_frame_by_the_subscribers_parse_of_it(tmp_path, middleware, width):
    """The guard's checker is a copy of the subscriber: its delay grows as the subscriber's."""
    design = compile_spec(write_spec(tmp_path, spec_text(middleware, width, JOINTS),
                                     pass__py=PASS_THROUGH))  # fmt: skip
    (converter,) = design.infrastructure.subscribers
    types = message_types(middleware.lower())
    offsets = set()
    for count in (0, 2, MAXIMA.sequence):
        values = joint_state(count, middleware == "ROS1")
        frame = types.serialize(types.build(JOINTS, values), JOINTS)  # rosbags' bytes
        flat = {
            "header.stamp.sec": 3, "header.stamp.nanosec": 7, "header.frame_id": "base",
            "name": values["name"], "position": values["position"],
            "velocity": values["velocity"], "effort": values["effort"],
        }  # fmt: skip
        if middleware == "ROS1":
            flat["header.seq"] = 1
        beats, cycles = guard_latency(converter, design.project.maxima, flat)
        assert beats == math.ceil(len(frame) / (width // 8))
        assert cycles > beats  # one beat a cycle at most, then the verdict
        offsets.add(cycles - subscriber_latency(converter, design.project.maxima, flat))
    assert len(offsets) == 1  # the same constant whatever the frame's length
    assert 0 < offsets.pop() <= 4


def test_a_measurement_leaves_no_signal_behind_in_myhdl(tmp_path):
    """A build measures every converter; MyHDL resets every signal it knows after each run."""
    design = compile_spec(write_spec(tmp_path, spec_text("ROS2", 64, JOINTS),
                                     pass__py=PASS_THROUGH))  # fmt: skip
    (converter,) = design.infrastructure.subscribers
    known = len(myhdl_simulator._signals)
    assert subscriber_latency(converter, design.project.maxima) > 0
    assert len(myhdl_simulator._signals) == known


def test_a_drop_gate_adds_no_cycle():
    assert gate_latency() == 0


def test_the_report_lists_the_gate_and_the_guard_in_front_of_their_subscribers(tmp_path):
    rows = {}
    for message in (POINT, JOINTS):
        folder = tmp_path / message.rsplit("/", 1)[1]
        folder.mkdir()
        spec = write_spec(folder, spec_text("ROS2", 64, message), pass__py=PASS_THROUGH)
        result = run_rfc("build", spec, "-o", folder / "build")
        assert result.returncode == 0, result.stderr
        report = (folder / "build" / "report.md").read_text()
        latencies = report.split("## Latencies")[1].split("\n## ")[0]
        row = r"^\| (drop gate|frame guard) \| `sub` \| ([^|]+?) \|"
        rows[message] = re.findall(row, latencies, re.MULTILINE)
    assert rows[POINT] == [("drop gate", "0")]
    design = compile_spec(folder / "spec.yaml")
    (converter,) = design.infrastructure.subscribers
    _, cycles = guard_latency(converter, design.project.maxima)
    extra = cycles - subscriber_latency(converter, design.project.maxima)
    assert rows[JOINTS] == [("frame guard", f"{cycles} (subscriber + {extra})")]
