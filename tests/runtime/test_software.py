"""ROS-SW accelerators: Python specs, several inputs, and what a function may return."""

from __future__ import annotations

import shutil

import pytest

from rfc.driver import compile_spec
from rfc.errors import RfcError
from rfc.ir.pass_through import pass_through_routes
from rfc.lower.runtime_plan import DesignPlan
from rfc.runtime.core import Runtime
from rfc.runtime.loopback import PassThroughLogic
from rfc.runtime.replay import replay
from tests.runtime.support import SYSTEMS, compiled, pose_messages

POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"

PAIR = """\
project: {name: Pair, middleware: ROS2, scheduler: LRU}
accelerators:
  - name: AddX
    type: ROS-SW
    sources: ./pair.py
    interface:
      input: [{name: a, message: geometry_msgs/PoseWithCovarianceStamped},
              {name: b, message: geometry_msgs/PoseWithCovarianceStamped}]
      output: [{name: sum, message: geometry_msgs/PoseWithCovarianceStamped},
               {name: copy, message: geometry_msgs/PoseWithCovarianceStamped}]
blocks:
  - {name: A_sub, type: ROS>accelerator, message: geometry_msgs/PoseWithCovarianceStamped,
     topic: /a, outgoing: [{name: Add, port: a}]}
  - {name: B_sub, type: ROS>accelerator, message: geometry_msgs/PoseWithCovarianceStamped,
     topic: /b, outgoing: [{name: Add, port: b}]}
  - {name: Add, type: AddX, outgoing: [{name: Sum_pub, from: sum}, {name: Copy_pub, from: copy}]}
  - {name: Sum_pub, type: accelerator>ROS, message: geometry_msgs/PoseWithCovarianceStamped,
     topic: /sum}
  - {name: Copy_pub, type: accelerator>ROS, message: geometry_msgs/PoseWithCovarianceStamped,
     topic: /copy}
"""

PAIR_PY = """\
from dataclasses import replace


def AddX(a, b):
    position = replace(a.pose.pose.position, x=a.pose.pose.position.x + b.pose.pose.position.x)
    total = replace(a, pose=replace(a.pose, pose=replace(a.pose.pose, position=position)))
    return {"sum": total, "copy": b if b.header.frame_id != "map3" else None}
"""


def test_python_spec_runs_its_callables_as_the_yaml_spec_runs_its_files(tmp_path):
    shutil.copy(SYSTEMS / "passthrough.py", tmp_path)
    shutil.copy(SYSTEMS / "pose_mixed.py", tmp_path)
    python_design = compile_spec(tmp_path / "pose_mixed.py")
    yaml_design = compiled(tmp_path, "pose_mixed.yaml")
    assert python_design.infrastructure.software == yaml_design.infrastructure.software
    results = []
    for design in (python_design, yaml_design):
        runtime = Runtime(DesignPlan(design))
        messages = pose_messages(runtime.plan.types, 5)
        logic = PassThroughLogic(pass_through_routes(design))
        results.append(replay(runtime, messages, logic))
    assert results[0] == results[1]
    assert len(results[0]) == 5


def test_several_inputs_fire_on_the_newest_of_each_and_count_the_rest(tmp_path):
    (tmp_path / "pair.py").write_text(PAIR_PY)
    (tmp_path / "pair.yaml").write_text(PAIR)
    runtime = Runtime(DesignPlan(compile_spec(tmp_path / "pair.yaml")))
    messages = pose_messages(runtime.plan.types, 6)
    assert runtime.offer("/a", messages[0].data, 1) == []
    assert runtime.offer("/a", messages[1].data, 2) == []  # supersedes the first
    summed, copied = runtime.offer("/b", messages[2].data, 3)
    assert (summed.topic, summed.stamp, copied.topic) == ("/sum", 3, "/copy")
    total = runtime.plan.types.deserialize(summed.data, POSE)
    assert total.pose.pose.position.x == 0.5 + 1.0
    assert total.header.frame_id == "map1"
    assert runtime.offer("/b", messages[3].data, 4) == []  # waits for /a
    (only,) = runtime.offer("/a", messages[4].data, 5)  # b is map3: no copy
    assert only.topic == "/sum"
    runtime.offer("/a", messages[5].data, 6)
    runtime.finish()
    assert runtime.account.dropped == {("Add.a", "superseded"): 1, ("Add", "unmatched"): 1}
    assert runtime.account.software_calls == {"Add": 2}
    assert runtime.account.published == {"/sum": 2, "/copy": 1}


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("return a", "has 2 outputs and must return a tuple of 2 messages"),
        ('return {"total": a}', "returned output 'total', but its outputs are sum, copy"),
        ("return (a, b, a)", "must return a tuple of 2 messages"),
        ("a.pose.covariance = [1]\n    return (a, None)", "returned a message rosbags cannot"),
    ],
)
def test_what_a_function_returns_is_checked(tmp_path, body, message):
    (tmp_path / "pair.py").write_text(f"def AddX(a, b):\n    {body}\n")
    (tmp_path / "pair.yaml").write_text(PAIR)
    runtime = Runtime(DesignPlan(compile_spec(tmp_path / "pair.yaml")))
    first, second = pose_messages(runtime.plan.types, 2)
    runtime.offer("/a", first.data, 1)
    with pytest.raises(RfcError, match=message):
        runtime.offer("/b", second.data, 2)
