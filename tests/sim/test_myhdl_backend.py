"""The MyHDL backend on the echo fixture logic: every width, cut or not, equals the Python model."""

from __future__ import annotations

from functools import partial

import pytest
from myhdl import _simulator as myhdl_simulator

from rfc.ir.pass_through import pass_through_routes
from rfc.lower.runtime_plan import DesignPlan
from rfc.runtime.core import Runtime
from rfc.runtime.loopback import PassThroughLogic
from rfc.runtime.replay import replay
from rfc.sim.myhdl_sim import simulate_with_myhdl
from rfc.sim.settings import ReplaySettings
from tests.runtime.echo_top import echo_logic, route_table
from tests.runtime.support import compiled, pose_messages


@pytest.mark.parametrize(("width", "cut"), [(8, 5), (32, 0), (32, 3), (64, 1)])
def test_myhdl_simulation_of_the_logic_equals_the_python_model(tmp_path, width, cut):
    design = compiled(tmp_path, "pose_mixed.yaml", ("busWidth: 64", f"busWidth: {width}"))
    plan = DesignPlan(design)
    messages = pose_messages(plan.types, 4)
    expected = replay(Runtime(plan), messages, PassThroughLogic(pass_through_routes(design)))
    runtime = Runtime(plan)
    published = simulate_with_myhdl(
        partial(echo_logic, routes=route_table(design), cut_beats=cut),
        width,
        runtime,
        messages,
        clock_mhz=100.0,
        settings=ReplaySettings(drain_cycles=40, seed=width + cut),
    )
    assert [(p.topic, p.data) for p in published] == [(e.topic, e.data) for e in expected]
    assert runtime.account.from_logic == {"Pass_out0_pub": 4, "Pose_pub": 4}
    assert not runtime.account.dropped


def test_messages_closer_than_the_logic_needs_contend_in_the_queues(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    burst = [m.__class__(m.topic, m.type_name, 0, m.data) for m in pose_messages(plan.types, 14)]
    runtime = Runtime(plan)
    published = simulate_with_myhdl(
        partial(echo_logic, routes=route_table(design), cut_beats=0),
        64,
        runtime,
        burst,
        clock_mhz=100.0,
        settings=ReplaySettings(drain_cycles=40),
    )
    assert runtime.account.dropped == {("Pose_sub", "overflow"): 4}
    assert len(published) == 10


def test_progress_is_told_every_message_offered_in_order(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    messages = pose_messages(plan.types, 5)
    told: list[int] = []
    simulate_with_myhdl(
        partial(echo_logic, routes=route_table(design), cut_beats=0),
        64,
        Runtime(plan),
        messages,
        clock_mhz=100.0,
        settings=ReplaySettings(drain_cycles=40, progress=told.append),
    )
    assert told == list(range(1, len(messages) + 1))


def test_the_replay_leaves_no_signal_behind_in_myhdl(tmp_path):
    """MyHDL resets every signal it knows after each run: a replay's must go with it."""
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    known = len(myhdl_simulator._signals)
    simulate_with_myhdl(
        partial(echo_logic, routes=route_table(design), cut_beats=0),
        64,
        Runtime(plan),
        pose_messages(plan.types, 2),
        clock_mhz=100.0,
        settings=ReplaySettings(drain_cycles=40),
    )
    assert len(myhdl_simulator._signals) == known
