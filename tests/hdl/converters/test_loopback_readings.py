"""The converters in three readings — RTL VHDL, GHDL's netlist, Verilog — give rosbags' bytes.

Random bags whose strings and byte sequences take every length modulo the bus width go
through `rfc msg loopback` (subscriber → publisher) in GHDL on the VHDL, in GHDL on GHDL's
synthesized netlist and in Verilator on rfc's Verilog: every frame must come out as rosbags
serializes the message (fields outside the selection at their defaults), on the same cycles in
every reading, and GHDL must synthesize the converters without a warning (no latch, no
unassigned bit). A representative subset: every bus width with each middleware, selections
whole, included and excluded, and one case of each other type of the matrix (PointCloud2 on
each middleware); `tools/readings_matrix.py` runs the whole matrix.
"""

from __future__ import annotations

import subprocess
import zlib

import pytest

from rfc.lib.converters.loopback import LOOPBACK
from rfc.messages.rosbags_adapter import Middleware
from tests.hdl.converters.readings import READINGS, SPAN, Config, random_bag, run_reading

IMAGE, JOINTS = "sensor_msgs/msg/CompressedImage", "sensor_msgs/msg/JointState"
SCAN, CLOUD = "sensor_msgs/msg/LaserScan", "sensor_msgs/msg/PointCloud2"
POSE = "geometry_msgs/msg/PoseStamped"
ROS1, ROS2 = Middleware.ROS1, Middleware.ROS2
CONFIGS = [
    Config(IMAGE, ROS2, 8),
    Config(IMAGE, ROS1, 32, exclude=("format",)),
    Config(IMAGE, ROS2, 64, include=("data", "header.*")),
    Config(JOINTS, ROS1, 8, include=("name", "effort")),
    Config(JOINTS, ROS2, 32, exclude=("header.*",)),
    Config(JOINTS, ROS1, 64),
    Config(SCAN, ROS2, 32, exclude=("header.frame_id",)),
    Config(CLOUD, ROS2, 8),
    Config(CLOUD, ROS1, 64, exclude=("header.frame_id",)),
    Config(POSE, ROS1, 32),
]


@pytest.mark.slow
@pytest.mark.parametrize("config", CONFIGS, ids=lambda config: config.label)
def test_every_reading_sends_rosbags_bytes_on_the_same_cycles(config, tmp_path, monkeypatch):
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    bag = tmp_path / ("in.bag" if config.middleware is ROS1 else "in.mcap")
    random_bag(bag, config, seed=zlib.crc32(config.label.encode()))
    reports = {name: run_reading(bag, config, name, tmp_path / name) for name in READINGS}
    for name, report in reports.items():
        assert len(report.results) == SPAN, name
        assert [r.index for r in report.results if not r.equal] == [], name
    assert reports["netlist"].results == reports["rtl"].results
    assert reports["verilog"].results == reports["rtl"].results
    assert synthesis_warnings(tmp_path / "rtl") == []


def synthesis_warnings(workdir) -> list[str]:
    """GHDL's warnings when it synthesizes the loopback the run kept in `workdir`."""
    files = [workdir / "pck_myhdl_011.vhd", workdir / f"{LOOPBACK}.vhd"]
    options = ["--std=08", "-fsynopsys", f"--workdir={workdir}"]
    result = subprocess.run(
        ["ghdl", "--synth", *options, *files, "-e", LOOPBACK],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    return [line for line in result.stderr.splitlines() if "warning" in line]
