"""Benchmark: the message converters' latency, throughput and size; whole-bag loopbacks.

Latency and throughput come from GHDL running the generated subscriber wired to the generated
publisher (`rfc.lib.converters.loopback_run.run_frames`): the source never idles, the sink never
stalls, one message is in flight. Subscriber latency: first beat in -> fields valid; publisher
latency: fields given -> last beat out (that cycle included); throughput: beats per cycle while
a frame crosses each bus. LUT/FF come from GHDL synthesis + Yosys `synth_xilinx` (7-series).
Anchors (docs/architecture.md, Targets): Quaternion subscriber <= ceil(bytes/width) + 2
cycles (paper: 35 at 8 bits), publisher <= ceil(bytes/width) + 3 (paper: 28), >= 0.99
beats/cycle on a 640x480 Image, Image frame-length circuit <= 48 LUTs (the paper's figure).

Usage:
    .venv/bin/python tools/bench_converters.py [--no-synth] [--image-widths 64 32]
    .venv/bin/python tools/bench_converters.py --loopback [--widths 64 32 8]   # whole bags
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
from myhdl import ToVerilogWarning, ToVHDLWarning, block

ROOT = Path(__file__).resolve().parent.parent
BAGS = Path(os.environ.get("RFC_SHARED_DATA", ROOT.parent / "shared" / "data")) / "bags"

from rfc.lib.converters.build import generate  # noqa: E402
from rfc.lib.converters.frame_length import frame_length_circuit, length_formula  # noqa: E402
from rfc.lib.converters.loopback_run import loopback, run_frames  # noqa: E402
from rfc.lib.converters.plan import plan  # noqa: E402
from rfc.lib.converters.ports import Direction, Port, PortRole, Side, ports_of  # noqa: E402
from rfc.lib.converters.toplevel import port_signals, top_block  # noqa: E402
from rfc.messages.codec import default_values, encode  # noqa: E402
from rfc.messages.layout import flatten  # noqa: E402
from rfc.messages.limits import Limits  # noqa: E402
from rfc.messages.rosbags_adapter import Middleware, message_types  # noqa: E402
from rfc.toolchain import convert_myhdl, elaboration, estimate_resources  # noqa: E402

WIDTHS = (8, 32, 64)
QUATERNION = "geometry_msgs/msg/Quaternion"
IMAGE = "sensor_msgs/msg/Image"
#: Latency table: small fixed-size types and a few with strings and sequences.
LATENCY_TYPES = (QUATERNION, "geometry_msgs/msg/Twist", "sensor_msgs/msg/Imu")
#: The whole-bag loopbacks of issue 4: (bag, type, topic).
BAG_RUNS = (
    ("nav2_turtlebot.mcap", "nav_msgs/msg/Odometry", "/odom"),
    ("nav2_turtlebot.mcap", "geometry_msgs/msg/PoseWithCovarianceStamped", "/amcl_pose"),
    ("nav2_turtlebot.mcap", "tf2_msgs/msg/TFMessage", "/tf"),
    ("cdr_test_0.mcap", "test_msgs/msg/BasicTypes", None),
    ("cdr_test_0.mcap", "test_msgs/msg/Arrays", None),
)


def image_values(layout, height: int = 480, width: int = 640) -> dict:
    values = default_values(layout)
    values.update(
        {
            "header.frame_id": "camera",
            "height": height,
            "width": width,
            "encoding": "rgb8",
            "step": 3 * width,
            "data": np.arange(3 * width * height, dtype=np.uint32).astype(np.uint8) % 251,
        }
    )
    return values


def latency_rows(work: Path) -> list[str]:
    rows = []
    for type_name in LATENCY_TYPES:
        for middleware in (Middleware.ROS2, Middleware.ROS1):
            layout = flatten(message_types(middleware), type_name)
            frame = encode(layout, default_values(layout))
            for width in WIDTHS:
                converters = plan(layout, width, Limits(string=16, sequence=16, frame=4096))
                sent, timing = run_frames(converters, [frame], work / f"lat-{width}")[0]
                assert sent == frame, f"{type_name} {middleware} {width}: loopback differs"
                beats = -(-len(frame) // (width // 8))
                target = (
                    f"{beats + 2} / {beats + 3}" if type_name == QUATERNION else "-"
                )  # the targets (docs/architecture.md) cover only Quaternion
                rows.append(
                    row(
                        type_name.rsplit("/", 1)[-1],
                        middleware.value,
                        width,
                        len(frame),
                        beats,
                        timing.subscriber_cycles,
                        timing.publisher_cycles,
                        target,
                    )
                )
    return rows


def throughput_rows(work: Path, widths: list[int]) -> list[str]:
    layout = flatten(message_types(Middleware.ROS2), IMAGE)
    values = image_values(layout)
    frame = encode(layout, values)
    rows = []
    for width in widths:
        limits = Limits(string=16, sequence=1, frame=16, fields={"data": len(values["data"])})
        converters = plan(layout, width, limits)
        start = time.perf_counter()
        sent, timing = run_frames(converters, [frame], work / f"image-{width}")[0]
        assert sent == frame, f"Image {width}: loopback differs"
        rows.append(
            row(
                "Image 640x480 rgb8",
                width,
                len(frame),
                timing.beats_in,
                f"{timing.subscriber_throughput:.4f}",
                f"{timing.publisher_throughput:.4f}",
                timing.subscriber_cycles,
                timing.publisher_cycles,
                f"{time.perf_counter() - start:.0f}",
            )
        )
    return rows


@block
def frame_length_only(plan, **ports):
    """The frame-length circuit alone: the publisher's top-level length inputs, the length."""
    counts = {name: signal for name, signal in ports.items() if name != "frame_length"}
    return frame_length_circuit(plan, counts, ports["frame_length"])


def frame_length_resources(converters, work: Path):
    names = {stage.port for stage in length_formula(converters).stages if stage.port}
    ports: list[Port] = [p for p in ports_of(converters, Side.PUBLISHER) if p.name in names]
    output = Port("frame_length", 32, Direction.OUT, PortRole.FRAME_LENGTH)
    signals = port_signals([*ports, output])
    with elaboration(), warnings.catch_warnings():
        warnings.simplefilter("ignore", ToVHDLWarning)
        warnings.simplefilter("ignore", ToVerilogWarning)
        top = top_block("image_frame_length", list(signals), frame_length_only, plan=converters)
        files = convert_myhdl(top(**signals), "image_frame_length", work, verilog=False)
    return estimate_resources(files, "image_frame_length")


def resource_rows(work: Path) -> list[str]:
    rows = []
    for type_name in (QUATERNION, IMAGE):
        layout = flatten(message_types(Middleware.ROS2), type_name)
        for width in WIDTHS:
            converters = plan(layout, width, Limits(string=256, sequence=2**22 - 1, frame=4096))
            cells = []
            for side in Side:
                made = generate(converters, side, work / f"{type_name[-5:]}-{width}-{side.value}")
                cells.append(estimate_resources(made.vhdl, made.name))
            short = type_name.rsplit("/", 1)[-1]
            rows.append(row(short, width, cells[0].lut, cells[0].ff, cells[1].lut, cells[1].ff))
    # The circuit's adders are as wide as the configured maxima make the lengths.
    for label, limits in (
        ("strings <= 64, data <= 640x480x3", Limits(string=64, sequence=640 * 480 * 3)),
        ("strings <= 256, data < 2^22", Limits(string=256, sequence=2**22 - 1)),
    ):
        image = plan(flatten(message_types(Middleware.ROS2), IMAGE), 64, limits)
        circuit = frame_length_resources(image, work / f"frame-length-{limits.string}")
        rows.append(row(f"Image frame-length circuit ({label})", "-", circuit.lut, circuit.ff))
    return rows


def bag_rows(work: Path, widths: list[int]) -> list[str]:
    rows = []
    # Smallest runs first: a long run's rows still come out as each configuration finishes.
    runs = sorted(
        ((bag, type_name, topic, width) for bag, type_name, topic in BAG_RUNS for width in widths),
        key=lambda run: (run[3] != 64, run[3] != 32, run[0] != "cdr_test_0.mcap"),
    )
    for bag, type_name, topic, width in runs:
        start = time.perf_counter()
        report = loopback(type_name, BAGS / bag, topic=topic, width=width, workdir=work / "bag")
        sub = [r.subscriber_cycles for r in report.results]
        pub = [r.publisher_cycles for r in report.results]
        rows.append(
            row(
                bag,
                topic or "-",
                type_name,
                width,
                len(report.results),
                sum(r.equal for r in report.results),
                f"{min(sub)}-{max(sub)}",
                f"{min(pub)}-{max(pub)}",
                f"{time.perf_counter() - start:.0f}",
            )
        )
    return rows


def row(*cells: object) -> str:
    """Print one markdown table row as soon as it is measured, and return it."""
    text = "| " + " | ".join(map(str, cells)) + " |"
    print(text, flush=True)
    return text


def header(*columns: str, aligned: str) -> None:
    """Print a markdown table's header; `aligned` is its separator row."""
    print("| " + " | ".join(columns) + " |")
    print(aligned)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--loopback", action="store_true", help="whole-bag loopbacks only")
    parser.add_argument(
        "--widths", type=int, nargs="*", default=list(WIDTHS), help="widths for --loopback"
    )
    parser.add_argument("--no-synth", action="store_true", help="skip LUT/FF estimates")
    parser.add_argument(
        "--image-widths", type=int, nargs="*", default=[64, 32], help="widths for the Image run"
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="rfc-bench-conv-") as scratch:
        work = Path(scratch)
        if args.loopback:
            header(
                "bag",
                "topic",
                "type",
                "width",
                "messages",
                "byte-exact",
                "sub cycles",
                "pub cycles",
                "s",
                aligned="|---|---|---|---:|---:|---:|---:|---:|---:|",
            )
            rows = bag_rows(work, args.widths)
            return 0 if all(r.split("|")[5] == r.split("|")[6] for r in rows) else 1
        header(
            "type",
            "middleware",
            "width",
            "bytes",
            "beats",
            "sub cycles",
            "pub cycles",
            "target sub / pub",
            aligned="|---|---|---:|---:|---:|---:|---:|---|",
        )
        latency_rows(work)
        print()
        header(
            "message",
            "width",
            "bytes",
            "beats",
            "sub beats/cycle",
            "pub beats/cycle",
            "sub cycles",
            "pub cycles",
            "s",
            aligned="|---|---:|---:|---:|---:|---:|---:|---:|---:|",
        )
        throughput_rows(work, args.image_widths)
        if not args.no_synth:
            print()
            header(
                "converter",
                "width",
                "subscriber LUT",
                "subscriber FF",
                "publisher LUT",
                "publisher FF",
                aligned="|---|---:|---:|---:|---:|---:|",
            )
            resource_rows(work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
