"""Benchmark: the size of rfc's ap_ctrl wrapper around an HLS core, in LUTs and flip-flops.

Generates the logic of the HLS test systems (FrankaState folded by a struct-taking core; an
image inverted through hls::stream; the paper's RGB-to-gray stage, whose input port has two
streams, frame_id held in a FIFO) and maps each wrapper's Verilog with Yosys
``synth_xilinx -family xc7`` (`rfc.toolchain.yosys`). The Vitis core itself is not counted:
only Vitis HLS makes it.

Usage: .venv/bin/python tools/bench_hls_wrapper.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from rfc.driver import compile_spec
from rfc.lower.system.generate import generate_system
from rfc.toolchain.module_estimates import module_estimate

ROOT = Path(__file__).resolve().parents[1]
SYSTEMS = {
    "FrankaState → PointStamped (a struct each way; 64 inputs, 5 outputs captured)": ROOT
    / "tests/lower/system/hls_fold/fold.yaml",
    "Image → Image (struct + hls::stream<uint8_t> each way, 64-bit bus)": ROOT
    / "tests/lower/system/hls_invert/invert.yaml",
    "Image (header + data) → Image (two hls::stream each way, frame_id held: 16 characters, "
    "64-bit bus)": ROOT / "tests/lower/system/hls_gray/gray.yaml",
}


def main() -> None:
    """Print one table row per wrapper."""
    print("| wrapper of | LUT | FF | CARRY4 | LUTRAM | BRAM |")
    print("|---|---:|---:|---:|---:|---:|")
    for what, spec in SYSTEMS.items():
        with tempfile.TemporaryDirectory(prefix="rfc-bench-") as scratch:
            system = generate_system(compile_spec(str(spec)), Path(scratch))
            wrapper = next(p for p in system.verilog if p.stem.endswith("_ap_ctrl"))
            figures = module_estimate(wrapper, wrapper.stem).resources
        print(
            f"| {what} | {figures.lut} | {figures.ff} | {figures.carry} | {figures.lutram} "
            f"| {figures.bram} |"
        )


if __name__ == "__main__":
    main()
