"""The stall watchdog: a logic that stops moving ends `rfc sim` with an error, never a hang.

Two fixture logics stall in the two ways a logic can (tests/runtime/stuck_top.py): one never
takes a PS→PL beat, one starts a PL→PS transfer and never ends it. On every simulator `rfc sim`
exits 1 naming what was pending, writes no bag, and prints no traceback.
"""

from __future__ import annotations

import pytest

from rfc.messages.rosbags_adapter import message_types, write_bag
from rfc.runtime.stall import AnswerWait, StallError, StallWatch
from tests.runtime.support import pose_messages, system_copy
from tests.support.cli import run_rfc

POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"
STUCK = {
    "deaf": ("PS→PL transfer to subscriber 'Pose_sub'", "tests.runtime.stuck_top:deaf_top"),
    "babbling": (
        "a PL→PS transfer had begun and not ended (no tlast)",
        "tests.runtime.stuck_top:babbling_top",
    ),
}


@pytest.fixture
def bag(tmp_path):
    types = message_types("ros2")
    path = tmp_path / "in.mcap"
    messages = [(m.topic, m.timestamp_ns, m.data) for m in pose_messages(types, 3)]
    write_bag(path, types, {"/amcl_pose": POSE}, messages)
    return path


SIMULATORS = {
    "ghdl": ("--simulator", "ghdl"),
    "verilator": ("--simulator", "verilator"),
    "myhdl": ("--backend", "myhdl"),
}


@pytest.mark.parametrize("simulator", SIMULATORS)
@pytest.mark.parametrize("logic", STUCK)
def test_a_stalling_logic_ends_the_replay_with_what_was_pending(tmp_path, bag, simulator, logic):
    spec = system_copy(tmp_path, "pose_mixed.yaml")
    pending, provider = STUCK[logic]
    out = tmp_path / "out.mcap"
    result = run_rfc(
        "sim", spec, "--bag", bag, "--out", out, *SIMULATORS[simulator],
        "--top-provider", provider, "--stall-cycles", "3000",
    )  # fmt: skip
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert "error: the logic stalled: no DMA transfer completed for" in result.stderr
    assert "raise --stall-cycles" in result.stderr
    assert pending in result.stderr
    assert not out.exists()


def test_the_window_grows_with_the_longest_transfer_and_rests_while_idle():
    watch = StallWatch(stall_cycles=100, lanes=8)
    watch.check(50, busy=True, pending=lambda: "x")
    watch.completed(60, transfer_bytes=800)  # 100 beats
    assert watch.window() == 100 + 4 * 100
    watch.check(560, busy=True, pending=lambda: "x")  # exactly the window: not yet
    with pytest.raises(StallError, match=r"no DMA transfer completed for 501 cycles .* while x"):
        watch.check(561, busy=True, pending=lambda: "x")
    watch.check(5000, busy=False, pending=lambda: "x")  # idle: the watch rests
    watch.check(5500, busy=True, pending=lambda: "x")


def test_a_long_transfer_under_way_gets_its_time_before_it_completes():
    watch = StallWatch(stall_cycles=100, lanes=8, largest_output=8000)
    # the first PS→PL transfer: 8,000 bytes = 1,000 beats, nothing completed yet
    watch.check(3000, busy=True, pending=lambda: "x", sending_bytes=8000)
    # a PL→PS transfer under way may be as long as the largest publisher frame
    watch.check(3000, busy=True, pending=lambda: "x", receiving=True)
    with pytest.raises(StallError):
        watch.check(4200, busy=True, pending=lambda: "x", sending_bytes=8000)


def test_an_answer_is_awaited_four_times_the_transfer_until_the_logic_answers():
    answer = AnswerWait(lanes=8)
    assert not answer.awaiting(0)
    answer.sent(100, transfer_bytes=8000)  # 1,000 beats: awaited until cycle 4,100
    answer.sent(200, transfer_bytes=80)  # 10 beats: until cycle 240
    assert answer.awaiting(4099)
    answer.answered()  # the first transfer's answer; the second is past its time
    assert not answer.awaiting(300)
    answer.sent(5000, transfer_bytes=8)
    assert answer.awaiting(5003)
    assert not answer.awaiting(5004)
