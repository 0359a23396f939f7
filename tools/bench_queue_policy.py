"""The paper's §4.3 point, measured: one callback queue per subscriber against ROS's shared one.

The multi-type system (examples/multi_type: Image, LaserScan and TwistStamped subscribers,
pass-through accelerators, publishers) under two traffic patterns, with the PS→PL DMA's
transfer time modelled from message sizes and the bus width (rfc.runtime.timing). Prints the
figures as the Markdown table of docs/runtime.md.

    .venv/bin/python tools/bench_queue_policy.py [--seconds 2]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

import numpy as np

from rfc.driver import compile_spec
from rfc.lower.runtime_plan import DesignPlan
from rfc.messages.limits import Limits
from rfc.runtime.core import QueueConfig, QueuePolicy
from rfc.runtime.timing import Traffic, measure, transfer_ns

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "examples" / "multi_type" / "MultiType.yaml"
MS = 1_000_000
DEPTH = 10


def runtime_plan() -> DesignPlan:
    """The example's runtime, its maxima widened to full-HD images.

    The study is of the processor side (queues and the DMA's transfer times), with the paper's
    large frames; the example's own maxima size its logic's buffers for an xc7z020.
    """
    design = compile_spec(SPEC)
    fields = {"data": 1920 * 1080 * 3, "ranges": 2048, "intensities": 2048}
    full_hd = Limits(string=64, fields=fields)
    return DesignPlan(replace(design, project=replace(design.project, maxima=full_hd)))


def sample_messages(plan: DesignPlan) -> dict[str, bytes]:
    """A full-HD RGB image, a 1081-beam scan with intensities, and a twist, serialized."""
    types = plan.types
    image = types.build(
        "sensor_msgs/msg/Image",
        {
            "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "camera"},
            "height": 1080,
            "width": 1920,
            "encoding": "rgb8",
            "is_bigendian": 0,
            "step": 1920 * 3,
            "data": np.zeros(1920 * 1080 * 3, np.uint8),
        },
    )
    scan = types.build(
        "sensor_msgs/msg/LaserScan",
        {
            "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "laser"},
            "angle_min": -2.35,
            "angle_max": 2.35,
            "angle_increment": 0.004363,
            "time_increment": 0.0,
            "scan_time": 0.025,
            "range_min": 0.02,
            "range_max": 30.0,
            "ranges": np.ones(1081, np.float32),
            "intensities": np.ones(1081, np.float32),
        },
    )
    twist = types.build(
        "geometry_msgs/msg/TwistStamped",
        {
            "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "base"},
            "twist": {
                "linear": {"x": 0.5, "y": 0.0, "z": 0.0},
                "angular": {"x": 0.0, "y": 0.0, "z": 0.1},
            },
        },
    )
    return {
        "/camera/image": types.serialize(image, "sensor_msgs/msg/Image"),
        "/scan": types.serialize(scan, "sensor_msgs/msg/LaserScan"),
        "/cmd_vel": types.serialize(twist, "geometry_msgs/msg/TwistStamped"),
    }


def scenarios(data: dict[str, bytes]) -> dict[str, list[Traffic]]:
    """A bursty camera, a steady busy camera, and a camera the DMA cannot keep up with."""
    return {
        "bursty camera: 3 frames every 100 ms, scan 40 Hz, twist 50 Hz": [
            Traffic("/camera/image", data["/camera/image"], 100 * MS, burst=3),
            Traffic("/scan", data["/scan"], 25 * MS, phase_ns=1 * MS),
            Traffic("/cmd_vel", data["/cmd_vel"], 20 * MS, phase_ns=3 * MS),
        ],
        "steady camera at 100 Hz (DMA 78 % busy), scan 40 Hz, twist 1 kHz": [
            Traffic("/camera/image", data["/camera/image"], 10 * MS),
            Traffic("/scan", data["/scan"], 25 * MS, phase_ns=1 * MS),
            Traffic("/cmd_vel", data["/cmd_vel"], 1 * MS, phase_ns=300_000),
        ],
        "overloaded camera at 150 Hz (DMA needs 117 %), scan 40 Hz, twist 50 Hz": [
            Traffic("/camera/image", data["/camera/image"], 6_666_667),
            Traffic("/scan", data["/scan"], 25 * MS, phase_ns=1 * MS),
            Traffic("/cmd_vel", data["/cmd_vel"], 20 * MS, phase_ns=3 * MS),
        ],
    }


POLICIES = {
    f"per-subscriber LRU, depth {DEPTH} each": QueueConfig(QueuePolicy.PER_SUBSCRIBER, DEPTH),
    f"shared FIFO, depth {3 * DEPTH}": QueueConfig(QueuePolicy.SHARED_FIFO, 3 * DEPTH),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=2.0, help="simulated time per run")
    args = parser.parse_args()
    plan = runtime_plan()
    data = sample_messages(plan)
    project = plan.design.project
    print(f"Bus {project.bus_width} bits at {project.clock_mhz:g} MHz; transfer times: ", end="")
    times = {t: transfer_ns(len(f), project.bus_width, project.clock_mhz) for t, f in data.items()}
    print(", ".join(f"{t} {len(data[t])} B = {ns / 1e6:.3f} ms" for t, ns in times.items()) + "\n")
    for title, traffic in scenarios(data).items():
        print(f"**{title}** ({args.seconds:g} s)\n")
        print(
            "| queues | topic | arrived | delivered | dropped | stale | age mean / p95 / max (ms) |"
        )
        print("|---|---|---:|---:|---:|---:|---|")
        for name, queues in POLICIES.items():
            figures = measure(
                plan,
                traffic,
                queues,
                int(args.seconds * 1e9),
                bus_width=project.bus_width,
                clock_mhz=project.clock_mhz,
            )
            for topic, f in figures.items():
                ages = " / ".join(f"{f.age_ms(s):.2f}" for s in ("mean", "p95", "max"))
                counts = f"{f.arrived} | {f.delivered} | {f.dropped} | {f.stale}"
                print(f"| {name} | {topic} | {counts} | {ages} |")
        print()


if __name__ == "__main__":
    main()
