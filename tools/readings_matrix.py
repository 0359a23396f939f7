"""The converter matrix through three readings: RTL VHDL, GHDL's netlist, Verilog in Verilator.

For each message type, middleware, bus width and selection (whole; only the first string or
sequence; all but it), a random bag whose strings and byte sequences take every length
modulo the bus (tests/hdl/converters/readings.py) goes through `rfc msg loopback` in each
reading. A configuration passes when every reading sends rosbags' bytes for every message
on the same cycles. Prints one Markdown row per configuration as it finishes, with the seconds
each reading took (the Verilator column includes its compilation: each configuration is a new
model), then the totals; exits 1 on any mismatch.

    .venv/bin/python tools/readings_matrix.py [--types T ...] [--widths 8 32 64]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from rfc.messages.layout import FieldKind, flatten  # noqa: E402
from rfc.messages.rosbags_adapter import Middleware, message_types  # noqa: E402
from tests.hdl.converters.readings import READINGS, Config, random_bag, run_reading  # noqa: E402

TYPES = (
    "std_msgs/msg/String",
    "sensor_msgs/msg/CompressedImage",
    "sensor_msgs/msg/JointState",
    "sensor_msgs/msg/LaserScan",
    "sensor_msgs/msg/PointCloud2",
    "diagnostic_msgs/msg/DiagnosticArray",
    "geometry_msgs/msg/PoseStamped",
)


def configs(types: list[str], widths: list[int]) -> list[Config]:
    """Every type, middleware, width and selection (whole, include, exclude)."""
    found = []
    for type_name in types:
        for middleware in Middleware:
            layout = flatten(message_types(middleware), type_name)
            variable = [f.path for f in layout.fields if f.kind is not FieldKind.PRIMITIVE]
            chosen = (variable or [layout.fields[-1].path])[0]
            for width in widths:
                found += [
                    Config(type_name, middleware, width),
                    Config(type_name, middleware, width, include=(chosen,)),
                    Config(type_name, middleware, width, exclude=(chosen,)),
                ]
    return found


def check(config: Config, folder: Path) -> tuple[bool, int, dict[str, float]]:
    """Whether every reading gave rosbags' bytes on the same cycles; messages; seconds."""
    suffix = ".bag" if config.middleware is Middleware.ROS1 else ".mcap"
    bag = folder / f"in{suffix}"
    random_bag(bag, config, seed=zlib.crc32(config.label.encode()))
    seconds, results = {}, {}
    for name in READINGS:
        start = time.perf_counter()
        report = run_reading(bag, config, name, folder / name)
        seconds[name] = time.perf_counter() - start
        results[name] = report.results
    agree = all(r == results["rtl"] for r in results.values())
    return agree and all(r.equal for r in results["rtl"]), len(results["rtl"]), seconds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--types", nargs="+", default=list(TYPES))
    parser.add_argument("--widths", nargs="+", type=int, default=[8, 32, 64])
    args = parser.parse_args()
    print("| configuration | messages | equal | RTL s | netlist s | Verilog s |")
    print("|---|---:|---|---:|---:|---:|")
    totals = dict.fromkeys(READINGS, 0.0)
    failed = passed = 0
    for config in configs(args.types, args.widths):
        with tempfile.TemporaryDirectory(prefix="rfc-readings-") as scratch:
            ok, messages, seconds = check(config, Path(scratch))
        passed, failed = passed + ok, failed + (not ok)
        for name, value in seconds.items():
            totals[name] += value
        times = " | ".join(f"{seconds[name]:.1f}" for name in READINGS)
        print(f"| {config.label} | {messages} | {'yes' if ok else 'NO'} | {times} |", flush=True)
    spent = " | ".join(f"{totals[name]:.0f}" for name in READINGS)
    print(f"| **{passed} of {passed + failed} configurations** | | | {spent} |")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
