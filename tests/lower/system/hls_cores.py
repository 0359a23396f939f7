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
from rfc.messages.rosbags_adapter import MessageTypes, read_bag
from rfc.runtime.core import Published, QueueConfig
from rfc.sim.hardware import simulate_with_ghdl
from tests.support.cli import run_rfc
from tests.support.vendor_check import Record, run_script

ROOT = Path(__file__).resolve().parents[3]


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


def c_simulated(spec: Path, bag: Path, types: MessageTypes, folder: Path) -> list[bytes]:
    """What `rfc sim` publishes for `bag`, the HLS function C-simulated with g++."""
    out = folder / f"c{bag.suffix}"
    result = run_rfc("sim", spec, "--bag", bag, "--out", out, cwd=ROOT,
                     env={"XDG_CACHE_HOME": str(folder / "cache")})  # fmt: skip
    assert result.returncode == 0, result.stderr
    return [m.data for m in read_bag(out, types)]


def built_with_vitis_run(spec: Path, accelerator: str, folder: Path) -> tuple[Path, Record]:
    """`rfc build` of `spec` into ``folder/build``, and what its Vitis HLS run would do."""
    out = folder / "build"
    result = run_rfc("build", spec, "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    return out, run_script(out / "hls" / accelerator / "run.tcl", folder / "hls.log")


#: The paper's HLS image pipeline as the example specifies it (full-HD maxima).
IMAGE_PIPELINE = ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml"
#: Its full-HD maxima, and small ones whose buffers fit the part's block RAM.
SMALL_IMAGES = {
    "maxima: {string: 64, fields: {data: 6220800}}": "maxima: {string: 16, fields: {data: 192}}",
    "maxBytes: 6220900": "maxBytes: 300",
    "maxBytes: 1228900": "maxBytes: 1200",
}


def shrink_images(spec: Path) -> None:
    """Give a copy of the HLS image pipeline's spec small images (a no-op on other specs)."""
    text = spec.read_text()
    for full_hd, small in SMALL_IMAGES.items():
        text = text.replace(full_hd, small)
    spec.write_text(text)
