"""Benchmark: what dropping malformed frames in the logic costs (LUT/FF, 7-series).

Synthesizes (GHDL + Yosys `synth_xilinx`) the drop gate the system puts behind every subscriber
(`rfc.lib.converters.malformed`) and the Quaternion subscriber at each bus width, which now
also gives the reason of a rejected frame. The gate is combinational on the handshake, so it adds
no cycle of latency; its registers are the four 32-bit per-reason counters.

Usage:
    .venv/bin/python tools/bench_drop_gate.py
"""

from __future__ import annotations

import sys
import tempfile
import warnings
from pathlib import Path

from rfc.lib.converters.build import generate
from rfc.lib.converters.malformed import drop_gate, gate_ports
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side
from rfc.lib.converters.toplevel import elaboration, port_signals, top_block
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.toolchain import convert_myhdl, estimate_resources

QUATERNION = "geometry_msgs/msg/Quaternion"


def main() -> int:
    """Print a Markdown table of the gate's and the subscribers' LUT/FF."""
    print("| circuit | width | LUT | FF |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory(prefix="bench-gate-") as scratch:
        work = Path(scratch)
        ports = gate_ports()
        with elaboration(), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            top = top_block("drop_gate", [p.name for p in ports], drop_gate)
            files = convert_myhdl(top(**port_signals(ports)), "drop_gate", work, verilog=False)
        gate = estimate_resources(files, "drop_gate")
        print(f"| drop gate (4 counters of 32 bits) | - | {gate.lut} | {gate.ff} |")
        layout = flatten(message_types(Middleware.ROS2), QUATERNION)
        for width in (8, 32, 64):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                made = generate(plan(layout, width), Side.SUBSCRIBER, work / f"sub{width}")
            cells = estimate_resources(made.vhdl, made.name)
            print(f"| Quaternion subscriber (ROS 2) | {width} | {cells.lut} | {cells.ff} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
