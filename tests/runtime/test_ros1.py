"""The ROS 1 node, through its core: rospy cannot be installed here, so the tests run the
node's ROS-independent loop (`NodeCore`) on the plan a ROS 1 build ships, as rospy's callbacks
would drive it.
"""

from __future__ import annotations

import socket
import threading

from rfc.driver import compile_spec
from rfc.ir.pass_through import pass_through_routes
from rfc.messages.rosbags_adapter import message_types
from rfc.runtime.loopback import PassThroughLogic
from rfc.runtime.node import NodeCore
from rfc.runtime.plan import load_plan
from rfc.runtime.ros1 import ros1_name
from tests.runtime.support import system_copy
from tests.runtime.test_node import dma_over, fake_logic
from tests.support.cli import run_rfc

STAMPED = "geometry_msgs/msg/PoseStamped"


def stamped_messages(count: int) -> list[bytes]:
    types = message_types("ros1")
    return [
        types.serialize(
            types.build(
                STAMPED,
                {
                    "header": {"seq": i, "stamp": {"sec": i, "nanosec": 3}, "frame_id": f"f{i}"},
                    "pose": {
                        "position": {"x": 0.5 * i, "y": 1.0, "z": -2.0},
                        "orientation": {"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8},
                    },
                },
            ),
            STAMPED,
        )
        for i in range(count)
    ]


def test_the_ros1_node_loop_moves_messages_through_the_logic_from_the_shipped_plan(tmp_path):
    spec = system_copy(
        tmp_path,
        "pose_ros1.yaml",
        ("type: ROS-SW", "type: MyHDL"),
        ("outgoing: [{name: Pass, include: [header, pose.position]}]", "outgoing: [{name: Pass}]"),
    )
    out = tmp_path / "build"
    result = run_rfc("build", spec, "-o", out, "--no-hardware")
    assert result.returncode == 0, result.stderr
    plan = load_plan(out / "sw" / "pose_ros1_plan.json")
    assert plan.middleware.label == "ROS 1"
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    logic = PassThroughLogic(pass_through_routes(compile_spec(spec)), cut=24)
    threading.Thread(target=fake_logic, args=(theirs, logic), daemon=True).start()
    messages = stamped_messages(8)
    published = []
    done = threading.Event()

    def publish(message):
        published.append(message)
        if len(published) == len(messages):
            done.set()

    core = NodeCore(plan, dma_over(ours, plan.max_transfer), publish)
    core.start()
    for data in messages:
        core.on_message("/groundtruth", data)
    assert done.wait(20), f"only {len(published)} of {len(messages)} published"
    ours.shutdown(socket.SHUT_RDWR)
    account = core.stop()
    assert [(p.topic, p.message, p.data) for p in published] == [
        ("/groundtruth_position", STAMPED, data) for data in messages
    ]
    assert account.to_logic == {"Truth_sub": 8}
    assert not account.dropped


def test_ros1_spells_types_without_msg():
    assert ros1_name("geometry_msgs/msg/PoseStamped") == "geometry_msgs/PoseStamped"
