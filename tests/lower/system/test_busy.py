"""The top level's ``busy`` port: one bit per hardware accelerator, then per publisher."""

from __future__ import annotations

import re

from rfc.lower.hardware import simulation_top
from tests.runtime.support import compiled


def test_busy_watches_the_logics_accelerators_then_its_publishers_not_software(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    system = simulation_top(design, tmp_path / "hdl")
    publishers = [c.block for c in design.infrastructure.publishers]
    assert system.busy == ("Pass", "Pass2", *publishers)  # Clear runs on the processor
    assert "Pose_pub" in publishers
    assert len(publishers) == 2  # the crossing publisher into Clear, and Pose_pub
    vhdl = (tmp_path / "hdl" / f"{system.top}.vhd").read_text()
    verilog = (tmp_path / "hdl" / f"{system.top}.v").read_text()
    assert re.search(r"busy : out std_logic_vector\(3 downto 0\)", vhdl)
    assert re.search(r"output wire \[3:0\] busy", verilog)
