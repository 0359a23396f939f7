"""`rfc sim` of one system in its three readings: RTL VHDL, GHDL's netlist, rfc's Verilog.

Each reading replays the same bag through the same spec: the VHDL in GHDL (``--simulator
ghdl``), GHDL's synthesized netlist of every generated component with the structural top kept
(``--netlist``) and rfc's Verilog in Verilator (``--simulator verilator``). The replays keep
their cache (``RFC_CACHE_DIR``: compiled models) in the test's folder, apart from the user's.
"""

from __future__ import annotations

import json
from pathlib import Path

from tests.support.cli import run_rfc

#: The readings: ``rfc sim`` options of each.
READINGS = {
    "rtl": ("--simulator", "ghdl"),
    "netlist": ("--netlist",),
    "verilog": ("--simulator", "verilator"),
}


def replay_readings(spec: Path, bag: Path, folder: Path, *options: str) -> dict[str, Path]:
    """The output bag of each reading of the logic; every replay succeeds and drops nothing."""
    outputs = {}
    for name, extra in READINGS.items():
        out = folder / f"{name}.mcap"
        args = ("sim", spec, "--bag", bag, "--out", out, "--json", *options, *extra)
        result = run_rfc(*args, cwd=folder, env={"RFC_CACHE_DIR": str(folder / "cache")})
        assert result.returncode == 0, f"{name}: {result.stderr[-2000:]}"
        assert json.loads(result.stdout)["dropped"] == [], name
        outputs[name] = out
    return outputs
