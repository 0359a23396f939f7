"""The runtime plan as shipped: custom message types travel as definitions inside it."""

from __future__ import annotations

import shutil

import numpy as np

from rfc.messages.codec import default_values, encode
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.runtime.core import Runtime
from rfc.runtime.plan import load_plan
from tests.support.cli import run_rfc

STATE = "franka_msgs/msg/FrankaState"
SPEC = """\
project: {name: FrankaJoints, middleware: ROS2, scheduler: LRU, msg_paths: [./msg]}
accelerators:
  - name: FirstJoints
    type: ROS-SW
    sources: ./joints.py
    top: first_joints
    interface:
      input: [{message: franka_msgs/FrankaState}]
      output: [{message: geometry_msgs/Point}]
blocks:
  - {name: State_sub, type: ROS>accelerator, message: franka_msgs/FrankaState,
     topic: /franka_state, outgoing: [{name: Joints}]}
  - {name: Joints, type: FirstJoints, outgoing: [{name: Joints_pub}]}
  - {name: Joints_pub, type: accelerator>ROS, message: geometry_msgs/Point, topic: /joints}
"""
JOINTS = """\
from rosbags.typesys import Stores, get_typestore

Point = get_typestore(Stores.ROS2_HUMBLE).types["geometry_msgs/msg/Point"]


def first_joints(state):
    return Point(x=state.q[0], y=state.q[1], z=state.q[2])
"""


def test_franka_types_reach_the_node_through_the_plans_definitions(tmp_path, examples_dir):
    project = tmp_path / "franka"
    shutil.copytree(examples_dir / "franka" / "msg", project / "msg")
    (project / "joints.py").write_text(JOINTS)
    (project / "project.yaml").write_text(SPEC)
    out = tmp_path / "build"
    result = run_rfc("build", project / "project.yaml", "-o", out, "--no-hardware")
    assert result.returncode == 0, result.stderr
    state_layout = flatten(MessageTypes("ros2", msg_paths=(project / "msg",)), STATE)
    shutil.rmtree(project)  # neither the .msg files nor the spec are left
    plan = load_plan(out / "sw" / "franka_joints_plan.json")
    assert STATE in plan.messages.definitions
    runtime = Runtime(plan)
    answers = []
    for angles in np.random.default_rng(3).uniform(-2.8, 2.8, size=(4, 7)):
        values = default_values(state_layout)
        values.update({f"q[{i}]": float(angle) for i, angle in enumerate(angles)})
        (published,) = runtime.offer("/franka_state", encode(state_layout, values), 0)
        answers.append((published.topic, published.data, angles[:3]))
    for topic, data, expected in answers:
        assert topic == "/joints"
        point = plan.messages.deserialize(data, "geometry_msgs/msg/Point")
        np.testing.assert_array_equal([point.x, point.y, point.z], expected)
    assert runtime.account.software_calls == {"Joints": 4}
