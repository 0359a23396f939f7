"""`rfc sim` waits for an accelerator that computes without DMA traffic, and not forever.

A MyHDL accelerator that answers each Point 3,000 cycles after taking it — three times the
default drain window — gives every output with the default window on each simulator (GHDL,
Verilator, MyHDL's); one that takes its input and never answers ends the replay with a warning
naming it, not a hang.
"""

from __future__ import annotations

import json

import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.support.cli import run_rfc

POINT = "geometry_msgs/msg/Point"
ACCELERATORS = '''
from myhdl import Signal, always_comb, always_seq, block, intbv

DELAY = 3000


@block
def slow_copy(clk, rst, p, q):
    """Answers each Point with itself DELAY cycles after taking it."""
    count = Signal(intbv(0, min=0, max=DELAY + 1))
    holding = Signal(bool(0))

    @always_comb
    def hand():
        p.ready.next = not holding
        q.valid.next = holding and count == DELAY

    @always_seq(clk.posedge, reset=rst)
    def step():
        if p.valid and not holding:
            holding.next = True
            count.next = 0
            q.x.next = p.x
            q.y.next = p.y
            q.z.next = p.z
        elif holding and count < DELAY:
            count.next = count + 1
        elif holding and q.ready:
            holding.next = False

    return hand, step


@block
def never(clk, rst, p, q):
    """Takes every Point and never answers."""

    @always_comb
    def hand():
        p.ready.next = True
        q.valid.next = False
        q.x.next = p.x
        q.y.next = p.y
        q.z.next = p.z

    return hand


def identity(message):
    return message
'''
SPEC = """
project: {name: Slow, middleware: ROS2, busWidth: 64, clockMHz: 100, scheduler: LRU}
accelerators:
  - name: Slow
    type: MyHDL
    sources: ./slow.py
    top: TOP
    reference: ./slow.py:identity
    interface: {input: [{name: p, message: geometry_msgs/Point}],
                output: [{name: q, message: geometry_msgs/Point}]}
blocks:
  - {name: sub, type: ROS>accelerator, message: geometry_msgs/Point, topic: /in,
     outgoing: [{name: acc}]}
  - {name: acc, type: Slow, outgoing: [{name: pub}]}
  - {name: pub, type: accelerator>ROS, message: geometry_msgs/Point, topic: /out}
"""


def system(tmp_path, top):
    (tmp_path / "slow.py").write_text(ACCELERATORS)
    (tmp_path / "slow.yaml").write_text(SPEC.replace("TOP", top))
    types = message_types("ros2")
    points = [types.build(POINT, {"x": i + 0.5, "y": -i, "z": 2.0**i}) for i in range(3)]
    inputs = [("/in", 1_000_000 * (i + 1), types.serialize(p, POINT)) for i, p in enumerate(points)]
    write_bag(tmp_path / "in.mcap", types, {"/in": POINT}, inputs)
    return tmp_path / "slow.yaml", [data for _, _, data in inputs]


SIMULATORS = {
    "ghdl": ("--simulator", "ghdl"),
    "verilator": ("--simulator", "verilator"),
    "myhdl": ("--backend", "myhdl"),
}


@pytest.mark.parametrize("simulator", list(SIMULATORS))
def test_outputs_computed_longer_than_the_drain_window_are_not_lost(tmp_path, simulator):
    spec, inputs = system(tmp_path, "slow_copy")
    out = tmp_path / "out.mcap"
    result = run_rfc("sim", spec, "--bag", tmp_path / "in.mcap", "--out", out,
                     *SIMULATORS[simulator], "--json", cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["warnings"] == []
    assert [m.data for m in read_bag(out, message_types("ros2"))] == inputs


@pytest.mark.parametrize("simulator", list(SIMULATORS))
def test_an_accelerator_that_never_answers_ends_the_replay_with_a_warning(tmp_path, simulator):
    spec, _ = system(tmp_path, "never")
    out = tmp_path / "out.mcap"
    result = run_rfc("sim", spec, "--bag", tmp_path / "in.mcap", "--out", out,
                     *SIMULATORS[simulator], "--stall-cycles", "5000", "--json",
                     cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["to_logic"] == {"sub": 3}
    assert document["published"] == {}
    assert len(document["warnings"]) >= 1
    assert all("'acc'" in warning for warning in document["warnings"])
    assert "warning: " in result.stderr
    assert "'acc'" in result.stderr
