"""Benchmark: what dropping malformed frames in the logic costs (latency, LUT/FF/BRAM, 7-series).

Two circuits stand behind or in front of a subscriber (`rfc.lower.system.guards`): the drop
gate behind one whose consumers get only fixed-size fields, and the store-and-forward frame
guard in front of one that hands on strings or sequences. The gate is combinational on the
handshake (no cycle of latency) with four 32-bit counters. The guard is measured here in
MyHDL's simulator — cycles from a frame's first beat in to its first and last beat out, with
the source never idle and the subscriber always ready — and synthesized with GHDL + Yosys
`synth_xilinx` for its LUT/FF/block RAM, on JointState frames at the given maxima. The
Quaternion subscriber's size shows what giving the reason of a rejected frame costs.

Usage:
    .venv/bin/python tools/bench_malformed.py
"""

from __future__ import annotations

import sys
import tempfile
import warnings
from math import ceil
from pathlib import Path

from myhdl import StopSimulation, always, block, delay, instance

from rfc.lib.converters.build import generate
from rfc.lib.converters.guard import frame_guard, guard_ports
from rfc.lib.converters.malformed import drop_gate, gate_ports
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.messages.codec import default_values, encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.passes.frame_size import frame_bound
from rfc.toolchain import convert_myhdl, elaboration, estimate_resources

QUATERNION, JOINTS = "geometry_msgs/msg/Quaternion", "sensor_msgs/msg/JointState"
WIDTHS = (8, 32, 64)
#: The guard's maxima: 6 joints with names of up to 32 bytes.
MAXIMA = Limits(string=32, sequence=6)


def joint_frame(layout) -> bytes:
    """A JointState of 6 joints with 12-byte names and every sequence full."""
    values = default_values(layout)
    values["name"] = [f"joint_{i:06d}" for i in range(6)]
    for path in ("position", "velocity", "effort"):
        values[path] = [float(i) for i in range(6)]
    values["header.frame_id"] = "base_link"
    return encode(layout, values)


def guard_latency(converters, depth: int, frame: bytes) -> tuple[int, int]:
    """Cycles from the first beat in to the first and to the last beat out."""
    width = converters.width
    signals = port_signals(guard_ports(width))
    beats = [frame[i : i + width] for i in range(0, len(frame), width)]
    seen: dict[str, int] = {}

    @block
    def bench():
        clk, cycle = signals["clk"], [0]
        dut = frame_guard(converters, depth, **signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            signals["rst"].next = 1
            signals["m_axis_tready"].next = 1
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


def convert_to(work: Path, name: str, ports, body, **parameters) -> list[Path]:
    with elaboration(), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        top = top_block(name, [p.name for p in ports], body, **parameters)
        return convert_myhdl(top(**port_signals(ports)), name, work, verilog=False)


def main() -> int:
    """Print Markdown tables of the gate's, the guard's and the subscribers' figures."""
    with tempfile.TemporaryDirectory(prefix="bench-malformed-") as scratch:
        work = Path(scratch)
        gate = estimate_resources(convert_to(work / "gate", "drop_gate", gate_ports(),
                                             drop_gate), "drop_gate")  # fmt: skip
        print("| circuit | width | LUT | FF | BRAM36 |")
        print("|---|---:|---:|---:|---:|")
        print(f"| drop gate (4 counters of 32 bits) | - | {gate.lut} | {gate.ff} | 0 |")
        quaternion = flatten(message_types(Middleware.ROS2), QUATERNION)
        for width in WIDTHS:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                made = generate(plan(quaternion, width), Side.SUBSCRIBER, work / f"q{width}")
            cells = estimate_resources(made.vhdl, made.name)
            print(f"| Quaternion subscriber (ROS 2) | {width} | {cells.lut} | {cells.ff} | 0 |")
        joints = flatten(message_types(Middleware.ROS2), JOINTS)
        frame = joint_frame(joints)
        latencies = []
        for width in WIDTHS:
            lanes = width // 8
            converters = plan(joints, width, MAXIMA)
            depth = ceil((frame_bound(joints, MAXIMA) + 3) / lanes)
            name = f"guard{width}"
            files = convert_to(work / name, name, guard_ports(lanes), frame_guard,
                               plan=converters, depth=depth)  # fmt: skip
            cells = estimate_resources(files, name)
            print(f"| JointState frame guard (ROS 2, {depth} beats) | {width} | {cells.lut} | "
                  f"{cells.ff} | {cells.bram} |")  # fmt: skip
            latencies.append((width, len(frame), *guard_latency(converters, depth, frame)))
        print()
        print("| width | frame bytes | first beat out | last beat out | frame beats |")
        print("|---:|---:|---:|---:|---:|")
        for width, size, first, last in latencies:
            print(f"| {width} | {size} | {first} | {last} | {ceil(size / (width // 8))} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
