"""The processor side against a Python pass-through model of the logic: routes and account."""

from __future__ import annotations

import pytest

from rfc.driver import compile_spec
from rfc.errors import RfcError
from rfc.ir.pass_through import pass_through_routes
from rfc.lower.runtime_plan import DesignPlan
from rfc.passes.pipeline import MODEL_PIPELINE
from rfc.runtime.core import QueueConfig, QueuePolicy, Runtime
from rfc.runtime.loopback import PassThroughLogic
from rfc.runtime.protocol import Chunk, ChunkFlags
from rfc.runtime.replay import replay
from tests.runtime.support import compiled, pose_messages, system_copy

POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"


def run(design, messages, cut=0, queues=None):
    runtime = Runtime(DesignPlan(design), queues)
    logic = (
        PassThroughLogic(pass_through_routes(design), cut)
        if design.infrastructure.subscribers
        else None
    )
    return runtime, replay(runtime, messages, logic)


@pytest.mark.parametrize("cut", [0, 40])
def test_mixed_system_runs_software_between_two_hardware_parts(tmp_path, cut):
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    messages = pose_messages(plan.types, 12)
    runtime, published = run(design, messages, cut)
    assert [p.stamp for p in published] == [m.timestamp_ns for m in messages]
    for message, output in zip(messages, published, strict=True):
        before = plan.types.deserialize(message.data, POSE)
        after = plan.types.deserialize(output.data, POSE)
        assert output.topic == "/pose_cleared"
        assert after.pose.pose.position.x == 2 * before.pose.pose.position.x
        assert not after.pose.covariance.any()
        assert after.header.frame_id == before.header.frame_id
    account = runtime.account
    assert account.received == {"/amcl_pose": 12}
    assert account.published == {"/pose_cleared": 12}
    assert account.to_logic == {"Pose_sub": 12, "Pass2_in0_sub": 12}
    assert account.from_logic == {"Pass_out0_pub": 12, "Pose_pub": 12}
    assert account.software_calls == {"Clear": 12}
    assert not account.dropped


@pytest.mark.parametrize(
    "switch",
    [
        [],
        [("type: MyHDL", "type: ROS-SW")],
        [("- {name: Pass, type: PassPose", "- {name: Pass, type: PassPoseSw")],
    ],
    ids=["hardware", "all-software", "first-pass-in-software"],
)
def test_switching_accelerators_to_software_changes_no_output(tmp_path, switch):
    software_type = """\
  - name: PassPoseSw
    type: ROS-SW
    sources: ./passthrough.py
    reference: identity
    interface:
      input: [{message: geometry_msgs/PoseWithCovarianceStamped}]
      output: [{message: geometry_msgs/PoseWithCovarianceStamped}]
blocks:"""
    reference = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(reference)
    messages = pose_messages(plan.types, 6)
    _, expected = run(reference, messages)
    (tmp_path / "variant").mkdir()
    variant = compiled(tmp_path / "variant", "pose_mixed.yaml", ("blocks:", software_type), *switch)
    runtime, published = run(variant, messages, cut=24)
    assert published == expected
    assert not runtime.account.dropped


def test_a_software_connection_carries_only_its_selection(tmp_path):
    design = compiled(
        tmp_path,
        "pose_mixed.yaml",
        ("{name: Clear}", "{name: Clear, include: [header, pose.pose]}"),
        ("type: MyHDL", "type: ROS-SW"),
    )
    plan = DesignPlan(design)
    messages = pose_messages(plan.types, 3)
    _, published = run(design, messages)
    first = plan.types.deserialize(published[2].data, POSE)
    assert first.header.frame_id == "map2"
    assert first.pose.pose.position.x == 2.0
    assert not first.pose.covariance.any()


def test_overflow_drops_the_oldest_and_counts_it(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    runtime = Runtime(DesignPlan(design), QueueConfig(QueuePolicy.PER_SUBSCRIBER, depth=2))
    messages = pose_messages(runtime.plan.types, 5)
    for message in messages:
        runtime.offer(message.topic, message.data, message.timestamp_ns)
    sent = [runtime.next_transfer() for _ in range(3)]
    assert sent[2] is None
    assert [queued.stamp for _, queued in sent[:2]] == [m.timestamp_ns for m in messages[3:]]
    assert runtime.account.dropped == {("Pose_sub", "overflow"): 3}


def test_protocol_errors_and_malformed_messages_are_counted(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    runtime = Runtime(DesignPlan(design))
    good = pose_messages(runtime.plan.types, 1)[0].data
    assert runtime.receive(b"\x01\x00", 0) == []
    assert runtime.receive(Chunk(9, ChunkFlags.WHOLE, 3, b"abc").to_bytes(), 0) == []
    assert runtime.receive(Chunk(0, ChunkFlags(0), len(good), good[:8]).to_bytes(), 0) == []
    assert (
        runtime.receive(Chunk(0, ChunkFlags.WHOLE, 5, b"\x00\x01\x00\x00\x07").to_bytes(), 0) == []
    )
    assert runtime.receive(Chunk(1, ChunkFlags.START, len(good), good[:8]).to_bytes(), 0) == []
    (published,) = runtime.receive(Chunk(0, ChunkFlags.WHOLE, len(good), good).to_bytes(), 5)
    assert (published.topic, published.stamp, published.data) == ("/pose_cleared", 5, good)
    runtime.finish()
    assert runtime.account.dropped == {
        ("logic", "protocol:short"): 1,
        ("logic", "protocol:id"): 1,
        ("Pose_pub", "protocol:orphan"): 1,
        ("Pose_pub", "malformed"): 1,
        ("Pass_out0_pub", "protocol:unfinished"): 1,
    }


def test_a_failing_software_accelerator_stops_the_run_with_its_message(tmp_path):
    path = system_copy(tmp_path, "pose_mixed.yaml", ("top: clear_covariance", "top: identity"))
    (tmp_path / "passthrough.py").write_text("def identity(message):\n    return 1 / 0\n")
    design = compile_spec(path, pipeline=MODEL_PIPELINE)  # its logic is PassThroughLogic
    runtime = Runtime(DesignPlan(design))
    message = pose_messages(runtime.plan.types, 1)[0]
    runtime.offer(message.topic, message.data, 0)
    chunk, _ = runtime.next_transfer()
    (back,) = PassThroughLogic(pass_through_routes(design)).transfer(chunk.to_bytes())
    with pytest.raises(RfcError, match=r"'Clear' raised ZeroDivisionError: division by zero"):
        runtime.receive(back, 0)


def test_a_software_accelerator_must_return_its_output_type(tmp_path):
    path = system_copy(tmp_path, "pose_mixed.yaml", ("type: MyHDL", "type: ROS-SW"))
    (tmp_path / "passthrough.py").write_text(
        "def identity(message):\n    return message.pose\n\n"
        "def clear_covariance(m):\n    return m\n"
    )
    runtime = Runtime(DesignPlan(compile_spec(path)))
    message = pose_messages(runtime.plan.types, 1)[0]
    with pytest.raises(RfcError, match="returned a geometry_msgs/msg/PoseWithCovariance on output"):
        runtime.offer(message.topic, message.data, 0)


def test_a_software_accelerator_without_its_function_is_reported(tmp_path):
    path = system_copy(tmp_path, "pose_mixed.yaml", ("top: clear_covariance", "top: clear_it"))
    with pytest.raises(RfcError, match="defines no function 'clear_it' for ROS-SW accelerator"):
        Runtime(DesignPlan(compile_spec(path)))
