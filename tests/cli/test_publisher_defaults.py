"""A publisher sent only part of a header builds: its frame length is static, GHDL accepts it."""

from __future__ import annotations

import tempfile
from pathlib import Path

from rfc.toolchain.ghdl import analyze
from tests.runtime.support import system_copy
from tests.support.cli import run_rfc


def test_a_publisher_including_a_header_without_frame_id_builds_and_elaborates(tmp_path):
    spec = system_copy(
        tmp_path,
        "pose_ros1.yaml",
        ("type: ROS-SW", "type: MyHDL"),
        (", include: [header, pose.position]", ""),
        ("[{name: Truth_pub}]", "[{name: Truth_pub, include: [header.stamp, pose]}]"),
    )
    out = tmp_path / "out"
    result = run_rfc("build", spec, "-o", out)
    assert result.returncode == 0, result.stderr
    hw = out / "hw"
    files = [hw / name for name in (hw / "files.txt").read_text().split()]
    with tempfile.TemporaryDirectory() as work:
        analyze(files, Path(work), top="pose_ros1_pl")  # raises GhdlError with GHDL's words
    publisher = (hw / "truth_pub_publisher.vhd").read_text()
    assert "frame_id" not in publisher.lower()
