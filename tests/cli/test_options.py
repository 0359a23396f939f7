"""Options several commands share: each command accepts and refuses the same values."""

from __future__ import annotations

import pytest

from tests.support.cli import run_rfc

# The arguments each command needs before it reads --simulator (refused before anything runs).
TAKES_A_SIMULATOR = {
    "sim": ("sim", "system.yaml", "--bag", "in.mcap", "--out", "out.mcap"),
    "msg loopback": ("msg", "loopback", "std_msgs/msg/String", "--bag", "in.mcap"),
}


@pytest.mark.parametrize("command", sorted(TAKES_A_SIMULATOR))
def test_every_simulator_choice_offers_ghdl_and_verilator_and_nothing_else(command, tmp_path):
    result = run_rfc(
        *TAKES_A_SIMULATOR[command], "--simulator", "modelsim", cwd=tmp_path, env={"COLUMNS": "200"}
    )
    assert result.returncode == 2
    assert "'modelsim' is not one of 'ghdl', 'verilator'" in result.stderr
    assert not list(tmp_path.iterdir())
