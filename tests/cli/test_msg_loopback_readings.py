"""`rfc msg loopback --netlist`: GHDL's synthesized netlist of the converters, as the RTL does.

The whole matrix of readings is in tests/hdl/converters/test_loopback_readings.py; here the
command line: the option, its report, the netlist it keeps, and its refusal of Verilator.
"""

from __future__ import annotations

import json

from rfc.messages.rosbags_adapter import Middleware
from tests.hdl.converters.readings import SPAN, Config, random_bag
from tests.support.cli import run_rfc

#: Strings of every length modulo the bus; at 8 bits the converters' tkeep is a single bit.
STRING = Config("std_msgs/msg/String", Middleware.ROS2, 8)


def test_the_netlist_of_the_converters_gives_the_rtls_report(tmp_path):
    bag = tmp_path / "strings.mcap"
    random_bag(bag, STRING, seed=8)
    args = ("msg", "loopback", STRING.type_name, "--bag", bag, "--width", "8", "--json")
    rtl = run_rfc(*args, "--simulator", "ghdl", cwd=tmp_path)
    netlist = run_rfc(*args, "--netlist", "--keep", "kept", cwd=tmp_path)
    assert rtl.returncode == 0, rtl.stderr
    assert netlist.returncode == 0, netlist.stderr
    report = json.loads(netlist.stdout)
    assert report["messages"] == SPAN
    assert report["equal"] is True
    assert report == json.loads(rtl.stdout)
    assert (tmp_path / "kept/rfc_loopback_netlist.vhd").is_file()


def test_the_netlist_is_simulated_in_ghdl_only(tmp_path):
    bag = tmp_path / "strings.mcap"
    random_bag(bag, STRING, seed=8)
    args = ("msg", "loopback", STRING.type_name, "--bag", bag, "--netlist")
    result = run_rfc(*args, "--simulator", "verilator", cwd=tmp_path)
    assert result.returncode == 2
    assert "--netlist simulates VHDL netlists: use --simulator ghdl" in result.stderr
    assert "Traceback" not in result.stderr
