"""The manager's registered boundaries, as Yosys synthesizes its generated Verilog.

Every bit the manager hands another block (the DMA, the converters, the status reader) must
be the output of a flip-flop: no combinational path then runs through it from one block into
another. Checked on Yosys' generic netlist, whatever shape the manager has.
"""

from __future__ import annotations

import json
import shutil
import subprocess

import pytest

from rfc.lib.manager.entity import ManagerShape
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.lower.system.components import manager_component
from rfc.toolchain.module_estimates import module_estimate

#: Yosys' internal flip-flop cells (every kind of reset and enable), and nothing else.
FLIP_FLOP_PREFIXES = ("$_DFF_", "$_DFFE_", "$_SDFF_", "$_SDFFE_", "$_SDFFCE_")


def drivers(verilog, top, workdir):
    """Per output port of `top`, the cell type driving each of its bits ('const' for 0/1)."""
    out = workdir / "netlist.json"
    script = f"read_verilog {verilog}; synth -flatten -top {top}; opt_clean; write_json {out}"
    result = subprocess.run(
        [shutil.which("yosys") or "yosys", "-q", "-p", script],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    module = json.loads(out.read_text())["modules"][top]
    driven = {}
    for cell in module["cells"].values():
        for pin, bits in cell["connections"].items():
            if cell["port_directions"][pin] == "output":
                driven.update(dict.fromkeys(bits, cell["type"]))
    return {
        name: [driven.get(bit, "const" if bit in ("0", "1") else "input") for bit in port["bits"]]
        for name, port in module["ports"].items()
        if port["direction"] == "output"
    }


@pytest.mark.parametrize(
    ("subscribers", "publishers", "scheduler"),
    [(1, 1, SchedulerSpec.create(Algorithm.LRU, 2)), (2, 3, SchedulerSpec.create("PFP", 3))],
)
def test_every_output_of_the_manager_comes_from_a_flip_flop(
    tmp_path, subscribers, publishers, scheduler
):
    shape = ManagerShape(64, subscribers, publishers, scheduler)
    component = manager_component(shape, tmp_path, "manager")
    verilog = next(path for path in component.verilog if path.suffix == ".v")
    outputs = drivers(verilog, "manager", tmp_path)
    expected = {"s_axis_mm2s_tready", "error_count"}
    expected |= {f"m_axis_s2mm_{name}" for name in ("tdata", "tkeep", "tvalid", "tlast")}
    expected |= {f"sub{i}_{n}" for i in range(subscribers) for n in ("tdata", "tvalid", "tlast")}
    expected |= {f"pub{j}_tready" for j in range(publishers)}
    assert expected <= set(outputs)
    combinational = {
        name: sorted(set(kinds) - {"const"})
        for name, kinds in outputs.items()
        if any(kind != "const" and not kind.startswith(FLIP_FLOP_PREFIXES) for kind in kinds)
    }
    assert combinational == {}


@pytest.mark.slow
def test_the_manager_meets_100_mhz_with_margin(tmp_path, monkeypatch):
    """Yosys' STA of the quaternion system's manager: well under half of 10 ns of cells."""
    monkeypatch.setenv("RFC_CACHE_DIR", str(tmp_path / "cache"))
    shape = ManagerShape(64, 1, 1, SchedulerSpec.create(Algorithm.LRU, 2))
    component = manager_component(shape, tmp_path, "manager")
    verilog = next(path for path in component.verilog if path.suffix == ".v")
    timing = module_estimate(verilog, "manager").timing
    assert timing is not None
    # the 2x routing allowance of docs/performance.md leaves 5 ns of cells at 100 MHz
    assert timing.delay_ps <= 4000, timing
