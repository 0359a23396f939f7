"""Run rfc's vendor scripts under recording stand-ins (tests/support/vendor_stubs.tcl) and check
what they did: files exist, cells are known IP or generated entities, every pin referenced exists
on its cell, every net has one driver, and every input of a generated cell is connected once."""

from __future__ import annotations

import re
import shutil
import subprocess
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from pathlib import Path

STUBS = Path(__file__).with_name("vendor_stubs.tcl")

# The IP cells rfc's block design uses: pins as (name, direction) and interface names, from
# Xilinx's product guides (PG082 processing_system7, PG021 axi_dma, PG164 proc_sys_reset,
# PG059 axi_interconnect, xlconcat and xlconstant utility IP).
_IP_PINS = {
    "xilinx.com:ip:processing_system7:5.5": (
        {
            "FCLK_CLK0": "out",
            "FCLK_RESET0_N": "out",
            "M_AXI_GP0_ACLK": "in",
            "S_AXI_HP0_ACLK": "in",
            "IRQ_F2P": "in",
        },
        {"M_AXI_GP0", "S_AXI_HP0", "DDR", "FIXED_IO"},
    ),
    "xilinx.com:ip:axi_dma:7.1": (
        {
            "s_axi_lite_aclk": "in",
            "m_axi_mm2s_aclk": "in",
            "m_axi_s2mm_aclk": "in",
            "m_axi_sg_aclk": "in",
            "axi_resetn": "in",
            "mm2s_introut": "out",
            "s2mm_introut": "out",
        },
        {"S_AXI_LITE", "M_AXI_MM2S", "M_AXI_S2MM", "M_AXI_SG", "M_AXIS_MM2S", "S_AXIS_S2MM"},
    ),
    "xilinx.com:ip:proc_sys_reset:5.0": (
        {
            "slowest_sync_clk": "in",
            "ext_reset_in": "in",
            "interconnect_aresetn": "out",
            "peripheral_aresetn": "out",
            "peripheral_reset": "out",
        },
        set(),
    ),
    "xilinx.com:ip:axi_interconnect:2.1": (
        {"ACLK": "in", "ARESETN": "in"}
        | {
            f"{side}{i:02d}_{kind}": "in"
            for side in "SM"
            for i in range(4)
            for kind in ("ACLK", "ARESETN")
        },
        {f"{side}{i:02d}_AXI" for side in "SM" for i in range(4)},
    ),
    "xilinx.com:ip:xlconcat:2.1": ({"In0": "in", "In1": "in", "dout": "out"}, set()),
    "xilinx.com:ip:xlconstant:1.1": ({"dout": "out"}, set()),
}

_PORT = re.compile(
    r"^\s*(\w+)\s*:\s*(in|out)\s+(std_logic_vector|std_logic|unsigned|signed)", re.M | re.I
)
_ENTITY = re.compile(r"^\s*entity\s+(\w+)\s+is(.*?)end\s+entity", re.M | re.I | re.S)


@dataclass
class Record:
    """What a script did under the stand-ins."""

    calls: list[tuple[str, list[list[str]]]] = field(default_factory=list)

    def of(self, command: str) -> list[list[list[str]]]:
        return [args for name, args in self.calls if name == command]


def run_script(script: Path, log: Path) -> Record:
    """Run a tcl script with the stand-ins; return its record (raises on a Tcl error)."""
    tclsh = shutil.which("tclsh")
    assert tclsh, "tclsh is installed by tools/setup.sh"
    result = subprocess.run(
        [tclsh, str(STUBS), str(log), str(script)], capture_output=True, text=True, check=False
    )
    assert result.returncode == 0, result.stderr
    record = Record()
    # Not splitlines(): it also splits at \x1e and \x1f.
    for line in log.read_text().split("\n"):
        if not line:
            continue
        name, *args = line.split("\x1f")
        record.calls.append((name, [a.split("\x1e") if a else [] for a in args]))
    return record


def entity_ports(files: list[Path]) -> dict[str, dict[str, str]]:
    """Entity name -> {port: direction} for every entity in the given VHDL files."""
    entities = {}
    for path in files:
        for name, body in _ENTITY.findall(path.read_text()):
            entities[name] = {p: d.lower() for p, d, _ in _PORT.findall(body)}
    return entities


_COMPONENT = re.compile(r"^\s*component\s+(\w+)\s+is(.*?)end\s+component", re.M | re.I | re.S)


def component_ports(files: list[Path]) -> dict[str, dict[str, str]]:
    """Component name -> {port: direction}: the vendor cores the top level declares."""
    components = {}
    for path in files:
        for name, body in _COMPONENT.findall(path.read_text()):
            components[name] = {p: d.lower() for p, d, _ in _PORT.findall(body)}
    return components


def check_vivado(record: Record) -> dict[str, dict[str, str]]:
    """Check a recorded Vivado build; return the generated cells' pins for further checks."""
    (added,) = record.of("add_files")[:1]
    files = [Path(f) for f in added[0]]
    for path in files:
        assert path.is_file(), f"add_files names a missing file: {path}"
    entities = entity_ports([f for f in files if f.suffix == ".vhd"])
    cells: dict[str, tuple[dict[str, str], set[str]]] = {}
    generated: dict[str, dict[str, str]] = {}
    for kind, (what,), (name,) in record.of("create_bd_cell"):
        assert name not in cells, f"cell {name} created twice"
        if kind[0] == "ip" and what.startswith("xilinx.com:hls:"):
            # an HLS core: its ports are the ones the top level declares for it (the contract
            # of rfc.hls.signature with Vitis HLS)
            core = what.split(":")[2]
            cores = component_ports([f for f in files if f.suffix == ".vhd"])
            assert core in cores, f"HLS core {core} is not declared by the generated VHDL"
            generated[name] = cores[core]
            cells[name] = (cores[core], set())
        elif kind[0] == "ip":
            assert what in _IP_PINS, f"unknown IP {what}"
            cells[name] = _IP_PINS[what]
        else:
            assert what in entities, f"module reference {what} is not in the added sources"
            generated[name] = entities[what]
            cells[name] = (entities[what], _interfaces(entities[what]))
    for (pin,) in record.of("get_bd_pins"):
        cell, _, port = pin[0].partition("/")
        assert cell in cells, f"pin {pin[0]} of unknown cell {cell}"
        assert port in cells[cell][0], f"cell {cell} has no pin {port}"
    for (pin,) in record.of("get_bd_intf_pins"):
        cell, _, port = pin[0].partition("/")
        assert cell in cells, f"interface {pin[0]} of unknown cell {cell}"
        assert port in cells[cell][1], f"cell {cell} has no interface {port}"
    uses: Counter[str] = Counter()
    for _, pins in record.of("connect_bd_net"):
        names = [p.removeprefix("pin:") for p in pins]
        drivers = [p for p in names if _direction(cells, p) == "out"]
        assert len(drivers) == 1, f"net of {names} has drivers {drivers}"
        uses.update(names)
    for (pair,) in record.of("connect_bd_intf_net"):
        for intf in pair:
            cell, _, prefix = intf.removeprefix("intf:").partition("/")
            members = [p for p in generated.get(cell, {}) if p.startswith(prefix + "_")]
            uses.update(f"{cell}/{p}" for p in members)
            uses[intf] += 1
    for pin, count in uses.items():
        assert count == 1, f"{pin} is connected {count} times"
    for cell, ports in generated.items():
        for port, direction in ports.items():
            if direction == "in":
                assert uses[f"{cell}/{port}"] == 1, f"input {cell}/{port} is not connected"
    return generated


def _interfaces(ports: dict[str, str]) -> set[str]:
    """AXI-Stream interfaces Vivado infers from port names (prefix_tdata, _tvalid, _tready)."""
    prefixes = defaultdict(set)
    for port in ports:
        prefix, _, suffix = port.rpartition("_")
        prefixes[prefix].add(suffix)
    return {p for p, s in prefixes.items() if {"tdata", "tvalid", "tready"} <= s}


def _direction(cells, pin: str) -> str:
    cell, _, port = pin.partition("/")
    return cells[cell][0][port]
