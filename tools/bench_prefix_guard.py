"""Benchmark: the prefix guard in front of a full-HD sensor_msgs/Image subscriber (7-series).

The prefix guard (`rfc.lib.converters.prefix_guard`) holds only the bytes before ``data``, so
its memory does not grow with the image. It is measured here at the image pipeline's
subscriber selection (header, height, width, data) and full-HD maxima (64-character strings,
6,220,800 bytes of data): LUT/FF/block RAM from GHDL + Yosys `synth_xilinx`, and in MyHDL's
simulator the cycles from a frame's first beat in to its first and its last beat out, with the
source never idle and the subscriber always ready, for a 64x48 mono8 image (the latency does
not depend on the image's size; after the prefix a beat passes per cycle).

Usage:
    .venv/bin/python tools/bench_prefix_guard.py
"""

from __future__ import annotations

import sys
import tempfile
import warnings
from dataclasses import replace
from math import ceil
from pathlib import Path

import numpy as np
from myhdl import StopSimulation, always, block, delay, instance

from rfc.lib.converters.plan import plan
from rfc.lib.converters.prefix_guard import DECLARED, prefix_guard, prefix_guard_ports
from rfc.lib.converters.prefix_plan import SLACK_BEATS, checking_plan
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import select
from rfc.passes.frame_size import frame_bound
from rfc.toolchain import convert_myhdl, elaboration, estimate_resources

IMAGE = "sensor_msgs/msg/Image"
MAXIMA = Limits(string=64, fields={"data": 1920 * 1080 * 3})
WIDTHS = (32, 64)


def image_frame() -> bytes:
    """A 64x48 mono8 image, serialized by rosbags."""
    types = message_types(Middleware.ROS2)
    tree = {"header": {"frame_id": "camera"}, "height": 48, "width": 64, "encoding": "mono8",
            "step": 64, "data": np.arange(64 * 48, dtype=np.uint8)}  # fmt: skip
    return types.serialize(types.build(IMAGE, tree), IMAGE)


def latency(checking, depth: int, frame: bytes) -> tuple[int, int]:
    """Cycles from the first beat in to the first and to the last beat out."""
    width = checking.width
    signals = port_signals(prefix_guard_ports(width))
    beats = [frame[i : i + width] for i in range(0, len(frame), width)]
    seen: dict[str, int] = {}

    @block
    def bench():
        clk, cycle = signals["clk"], [0]
        dut = prefix_guard(checking, depth, **signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            signals["rst"].next = 1
            signals["m_axis_tready"].next = 1
            signals[DECLARED].next = len(frame)
            yield clk.posedge
            signals["rst"].next = 0
            for index, beat in enumerate(beats):
                signals["s_axis_tdata"].next = int.from_bytes(beat, "little")
                signals["s_axis_tkeep"].next = (1 << len(beat)) - 1
                signals["s_axis_tlast"].next = index == len(beats) - 1
                signals["s_axis_tvalid"].next = 1
                yield clk.posedge
                while not signals["s_axis_tready"]:
                    yield clk.posedge
            signals["s_axis_tvalid"].next = 0

        @instance
        def watch():
            while True:
                yield clk.posedge
                cycle[0] += 1
                if signals["s_axis_tvalid"] and signals["s_axis_tready"]:
                    seen.setdefault("in", cycle[0])
                if signals["m_axis_tvalid"] and signals["m_axis_tready"]:
                    seen.setdefault("out", cycle[0])
                    if signals["m_axis_tlast"]:
                        seen["last"] = cycle[0]
                        raise StopSimulation

        return dut, clock, drive, watch

    with elaboration():
        bench().run_sim(quiet=1)
    return seen["out"] - seen["in"], seen["last"] - seen["in"] + 1


def main() -> int:
    """Print a Markdown table of the guard's size and latency at each bus width."""
    layout = select(flatten(message_types(Middleware.ROS2), IMAGE),
                    include=["header", "height", "width", "data"])  # fmt: skip
    frame = image_frame()
    empty = replace(MAXIMA, fields={"data": 0})
    print("| width | buffer beats | LUT | FF | BRAM36 | first out | last out | frame beats |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory(prefix="bench-prefix-guard-") as scratch:
        for width in WIDTHS:
            lanes = width // 8
            checking = checking_plan(plan(layout, width, MAXIMA))
            assert checking is not None
            bound = frame_bound(layout, empty)
            assert bound is not None
            depth = ceil(bound / lanes) + SLACK_BEATS
            name = f"prefix_guard{width}"
            ports = prefix_guard_ports(lanes)
            with elaboration(), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                top = top_block(name, [p.name for p in ports], prefix_guard, checking=checking,
                                depth=depth)  # fmt: skip
                files = convert_myhdl(top(**port_signals(ports)), name, Path(scratch) / name,
                                      verilog=False)  # fmt: skip
            cells = estimate_resources(files, name)
            first, last = latency(checking, depth, frame)
            print(f"| {width} | {depth} | {cells.lut} | {cells.ff} | {cells.bram} | {first} | "
                  f"{last} | {ceil(len(frame) / lanes)} |")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
