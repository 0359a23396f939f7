"""The ROS 2 node's device-independent logic: the runtime between callbacks and DMA devices."""

from __future__ import annotations

import os
import socket
import struct
import subprocess
import sys
import threading
import time

import pytest

from rfc.errors import RfcError
from rfc.ir.pass_through import pass_through_routes
from rfc.lower.runtime_plan import DesignPlan
from rfc.runtime.core import QueueConfig, Runtime
from rfc.runtime.dma_device import FileDma
from rfc.runtime.loopback import PassThroughLogic
from rfc.runtime.node import NodeCore
from rfc.runtime.replay import replay
from tests.runtime.support import compiled, pose_messages


def dma_over(sock: socket.socket, max_transfer: int = 1 << 20) -> FileDma:
    """The DMA on its own copy of the socket's descriptor.

    The node closes the DMA's descriptor and the socket closes its own when collected: sharing
    one number, the later close would hit whatever file has reused it by then.
    """
    descriptor = os.dup(sock.fileno())
    return FileDma(descriptor, descriptor, max_transfer)


def fake_logic(sock: socket.socket, logic: PassThroughLogic) -> None:
    """The other end of the DMA: answer each PS→PL transfer, one datagram per transfer."""
    while transfer := sock.recv(1 << 20):
        for answer in logic.transfer(transfer):
            sock.send(answer)
    sock.close()


def test_node_core_moves_messages_through_the_dma_devices(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    messages = pose_messages(plan.types, 20)
    expected = replay(Runtime(plan), messages, PassThroughLogic(pass_through_routes(design)))
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    logic = threading.Thread(
        target=fake_logic, args=(theirs, PassThroughLogic(pass_through_routes(design), cut=40))
    )
    logic.start()
    published = []
    done = threading.Event()

    def publish(message):
        published.append(message)
        if len(published) == len(messages):
            done.set()

    dma = dma_over(ours)
    core = NodeCore(plan, dma, publish, QueueConfig(depth=len(messages)), clock=lambda: 7)
    assert core.topics == ("/amcl_pose",)
    core.start()
    for message in messages:
        core.on_message(message.topic, message.data)
    assert done.wait(20), f"only {len(published)} of {len(messages)} published"
    ours.shutdown(socket.SHUT_RDWR)
    account = core.stop()
    logic.join(5)
    assert [(p.topic, p.data) for p in published] == [(e.topic, e.data) for e in expected]
    assert {p.stamp for p in published} == {7}
    assert account.published == {"/pose_cleared": 20}
    assert account.to_logic == {"Pose_sub": 20, "Pass2_in0_sub": 20}
    assert not account.dropped


def test_messages_offered_faster_than_the_dma_overflow_and_are_counted(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    core = NodeCore(plan, dma_over(ours), lambda _: None)
    for message in pose_messages(plan.types, 15):  # not started: nothing leaves the queue
        core.on_message(message.topic, message.data)
    ours.shutdown(socket.SHUT_RDWR)
    account = core.stop()
    theirs.close()
    assert account.dropped == {("Pose_sub", "overflow"): 5, ("Pose_sub", "unsent"): 10}


class SilentLogic:
    """DMA channels whose logic never takes a transfer (a bitstream that does not answer)."""

    def __init__(self):
        self.closed = threading.Event()

    def write(self, transfer):
        self.closed.wait()

    def read(self):
        self.closed.wait()
        return b""

    def close(self):
        self.closed.set()


def test_a_logic_that_takes_no_transfer_is_an_error_after_the_answer_timeout(tmp_path):
    plan = DesignPlan(compiled(tmp_path, "pose_mixed.yaml"))
    core = NodeCore(plan, SilentLogic(), lambda _: None)
    core.start()
    core.on_message("/amcl_pose", pose_messages(plan.types, 1)[0].data)
    core.check(timeout=0.2)  # just written: not yet late
    time.sleep(0.3)
    with pytest.raises(RfcError, match=r"the logic has not taken a PS→PL transfer in 0.2 s"):
        core.check(timeout=0.2)
    core.stop()


def test_the_node_imports_only_the_runtime_and_its_two_dependencies(tmp_path, examples_dir):
    """What the `runtime` extra promises: numpy and rosbags, no compiler, no simulator.

    The runtime reads the message layouts, the codec and the errors below it in the layers.
    """
    from tests.support.cli import run_rfc

    spec = examples_dir / "quaternion_to_euler" / "project.yaml"
    assert run_rfc("build", spec, "-o", tmp_path / "build", "--no-hardware").returncode == 0
    plan_file = tmp_path / "build" / "sw" / "quaternion_to_euler_plan.json"
    script = (
        "import sys\n"
        "from rfc.runtime.core import Runtime\n"
        "from rfc.runtime.plan import load_plan\n"
        "import rfc.runtime.node, rfc.runtime.ros1, rfc.runtime.ros2, rfc.runtime.transports\n"
        f"Runtime(load_plan(__import__('pathlib').Path({str(plan_file)!r})))\n"
        "print(' '.join(sorted({m.split('.')[0] for m in sys.modules} | "
        "{m for m in sys.modules if m.startswith('rfc.')})))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    loaded = set(result.stdout.split())
    below = ("rfc.runtime", "rfc.messages", "rfc.errors", "rfc.user_code")  # its layers
    assert {m for m in loaded if m.startswith("rfc.") and not m.startswith(below)} == set()
    assert not loaded & {"myhdl", "cocotb", "typer", "numba", "matplotlib", "rich", "rclpy"}
    assert {"numpy", "rosbags"} <= loaded


def test_the_node_reads_the_logics_drop_counters_and_logs_each_change(tmp_path):
    """A fake logic answers status requests as docs/protocol.md lays the answer out."""
    design = compiled(tmp_path, "pose_mixed.yaml")
    plan = DesignPlan(design)
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    subscribers = len(plan.subscriber_names)
    zero, drops = [0] * 4 * subscribers, [2, 0, 0, 1] + [0] * 4 * (subscribers - 1)
    readings = iter([zero, drops, zero, zero, drops])

    def answer():
        while (request := theirs.recv(64)) == struct.pack("<HHI", 0xFFFF, 3, 0):
            counts = next(readings)
            theirs.send(struct.pack("<HHI", 0xFFFF, 3, 4 * len(counts)) +
                        struct.pack(f"<{len(counts)}I", *counts))  # fmt: skip
        assert request == b""

    logic = threading.Thread(target=answer)
    logic.start()
    lines = []
    dma = dma_over(ours)
    core = NodeCore(plan, dma, lambda _: None, status_period=60, log=lines.append)
    core.start()
    assert core.read_status(10)
    assert lines == []  # nothing dropped yet: nothing to say
    assert core.read_status(10)
    first = plan.subscriber_names[0]
    assert lines == [
        f"frames the logic dropped: {first} logic:truncated 2, {first} logic:encoding 1"
    ]
    assert core.read_status(10)  # back to zero: said once
    assert core.read_status(10)  # the same again: not said
    account = core.stop()  # a last reading on the way out; closes the DMA (our end)
    ours.detach()
    logic.join(5)
    assert lines[1:] == ["frames the logic dropped: none", lines[0]]
    assert account.dropped == {(first, "logic:truncated"): 2, (first, "logic:encoding"): 1}
