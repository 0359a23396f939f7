"""Latency of the generated node's loop per message, measured on the quaternion example.

The node's core (`rfc.runtime.node.NodeCore`, what rclpy's callbacks drive) runs on the plan
``rfc build`` ships; each message is offered as a subscription callback would offer it, and the
time until the publish callback receives its answer is measured, one message in flight at a
time (latency), then back to back (throughput). Two transports:

- ``sim``: the build's logic co-simulated in GHDL (`--device sim`);
- ``echo``: a Python stand-in for the logic across a ``SOCK_SEQPACKET`` socket pair that answers
  each orientation with a fixed Point: the node loop's own cost (no simulator).

Prints the Markdown table of docs/runtime.md.

    .venv/bin/python tools/bench_node.py [--messages 200]
"""

from __future__ import annotations

import argparse
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types
from rfc.runtime.dma_device import DmaChannels, FileDma
from rfc.runtime.node import NodeCore
from rfc.runtime.plan import RuntimePlan, load_plan
from rfc.runtime.protocol import Chunk, message_chunk
from rfc.runtime.sim_device import SimulatedLogic

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "examples" / "quaternion_to_euler" / "project.yaml"
QUATERNION = "geometry_msgs/msg/Quaternion"
POINT = "geometry_msgs/msg/Point"


def orientations(count: int) -> list[bytes]:
    types = message_types("ros2")
    rng = np.random.default_rng(5)
    out = []
    for q in rng.normal(size=(count, 4)):
        x, y, z, w = q / np.linalg.norm(q)
        out.append(
            types.serialize(types.build(QUATERNION, {"x": x, "y": y, "z": z, "w": w}), QUATERNION)
        )
    return out


def echo_logic(plan: RuntimePlan) -> tuple[DmaChannels, Callable[[], None]]:
    """The logic as Python: each orientation answered with a Point by the publisher's id."""
    types = message_types("ros2")
    point = types.serialize(types.build(POINT, {"x": 0.0, "y": 0.0, "z": 0.0}), POINT)
    publisher = next(iter(plan.logic_outputs))
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)

    def answer() -> None:
        while transfer := theirs.recv(1 << 16):
            Chunk.from_bytes(transfer)
            theirs.send(message_chunk(publisher, point).to_bytes())
        theirs.close()

    thread = threading.Thread(target=answer, daemon=True)
    thread.start()
    descriptor = ours.detach()  # the node's DMA owns it and closes it when it stops
    return FileDma(descriptor, descriptor, plan.max_transfer), lambda: thread.join(5)


def measure(plan: RuntimePlan, dma: DmaChannels, messages: list[bytes]) -> dict[str, float]:
    """Per-message latency (one in flight) and back-to-back throughput, in microseconds."""
    arrived = threading.Semaphore(0)
    core = NodeCore(plan, dma, lambda _: arrived.release())
    core.start()
    topic = plan.inputs[0].topic
    for data in messages[:10]:  # warm-up
        core.on_message(topic, data)
        arrived.acquire(timeout=30)
    latencies = []
    for data in messages:
        start = time.perf_counter()
        core.on_message(topic, data)
        if not arrived.acquire(timeout=30):
            raise SystemExit("the logic did not answer")
        latencies.append(time.perf_counter() - start)
    start = time.perf_counter()
    burst = messages[: plan.document["queues"]["depth"]]
    for data in burst:
        core.on_message(topic, data)
    for _ in burst:
        arrived.acquire(timeout=30)
    per_message = (time.perf_counter() - start) / len(burst)
    core.stop()
    latencies.sort()
    return {
        "median": statistics.median(latencies) * 1e6,
        "p90": latencies[int(0.9 * (len(latencies) - 1))] * 1e6,
        "back_to_back": per_message * 1e6,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--messages", type=int, default=200)
    args = parser.parse_args()
    messages = orientations(args.messages)
    with tempfile.TemporaryDirectory(prefix="rfc-bench-node-") as scratch:
        out = Path(scratch) / "build"
        subprocess.run(
            [sys.executable, "-m", "rfc", "build", SPEC, "-o", out], check=True, capture_output=True
        )
        plan = load_plan(out / "sw" / "quaternion_to_euler_plan.json")
        rows = []
        dma, stop = echo_logic(plan)
        rows.append(("echo (Python logic, socket pair)", measure(plan, dma, messages)))
        stop()
        sim = SimulatedLogic.start(plan)
        rows.append(("sim (GHDL, generated logic)", measure(plan, sim, messages)))
    print(
        f"quaternion_to_euler, {args.messages} messages, one in flight; back to back: "
        f"{plan.document['queues']['depth']} at once"
    )
    print()
    print("| transport | median latency (µs) | p90 (µs) | back to back (µs/message) |")
    print("|---|---|---|---|")
    for name, figures in rows:
        print(
            f"| {name} | {figures['median']:.0f} | {figures['p90']:.0f} | "
            f"{figures['back_to_back']:.0f} |"
        )


if __name__ == "__main__":
    main()
