"""Running a generated system whose HLS core is replaced by a VHDL stand-in, in GHDL.

Vitis HLS is not here: a test writes the core Vitis HLS would export for its function (the
ports of docs/accelerators.md, "In the logic", and UG1399's ap_ctrl_hs, ap_none, ap_vld and
ap_fifo protocols) and replays a bag through the rest of the logic with it.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from rfc.driver import compile_spec
from rfc.lower.system.generate import generate_system
from rfc.runtime.core import Published, QueueConfig
from rfc.runtime.hardware import simulate_with_ghdl


@dataclass(frozen=True)
class Top:
    """The logic with the stand-in core, for `simulate_with_ghdl`."""

    top: str
    sources: list[Path]
    bus_width: int


def replay_with_stand_in(
    spec: Path, stand_in: str, bag: Path, topic: str, folder: Path
) -> list[Published]:
    """Replay `bag`'s `topic` through the logic of `spec`, the HLS core being `stand_in`."""
    design = compile_spec(str(spec))
    system = generate_system(design, folder / "hdl")
    core = folder / "hdl" / "stand_in.vhd"
    core.write_text(stand_in)
    package, *parts, top = system.files
    logic = Top(system.top, [package, core, *parts, top], system.bus_width)
    (folder / "sim").mkdir()
    run = simulate_with_ghdl(
        design, bag, {topic: topic}, logic, folder / "sim", queues=QueueConfig()
    )
    return run.published
