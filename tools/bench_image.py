"""Benchmark: cycles per input pixel of the image pipeline's three stages in the logic.

Feeds one rgb8 image (640x480 by default) at full rate — a data beat every cycle, as the
subscriber gives them, and every output beat taken at once — through RgbToGray → Downscale →
IntegralImage joined as the top level joins them, in MyHDL's simulator (the RTL rfc converts to
VHDL and Verilog), and counts the cycles from the first input data beat to the last output
beat. The output must equal NumPy's pipeline; the target is at most 1.1 cycles per input pixel.

Usage: .venv/bin/python tools/bench_image.py [--height H] [--width W] [--bus 64] [--json]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "image_pipeline"
sys.path.insert(0, str(EXAMPLE))

from image_bench import WITH_ENCODING, Picture, run_chain  # noqa: E402
from image_reference import pipeline  # noqa: E402
from stages import downscale, integral_image, rgb_to_gray  # noqa: E402

#: The issue's target: cycles per input pixel.
TARGET = 1.1


def main() -> int:
    """Print the cycles per input pixel; exit status 1 when the output or the target is missed."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--bus", type=int, default=64, choices=(32, 64))
    parser.add_argument("--json", action="store_true")
    arguments = parser.parse_args()
    rng = np.random.default_rng(1)
    shape = (arguments.height, arguments.width, 3)
    image = Picture(rng.integers(0, 256, size=shape, dtype=np.uint8), 1, 2, "camera")
    pixels = arguments.height * arguments.width
    start = time.perf_counter()
    run = run_chain(
        [rgb_to_gray, downscale, integral_image],
        [image],
        WITH_ENCODING,
        arguments.bus,
        limit=4 * pixels + 10_000,
    )
    seconds = time.perf_counter() - start
    equal = run.results[0].data == pipeline(image.pixels).tobytes()
    figures = {
        "height": arguments.height,
        "width": arguments.width,
        "bus": arguments.bus,
        "input_pixels": pixels,
        "cycles": run.cycles,
        "cycles_per_pixel": round(run.cycles / pixels, 4),
        "target": TARGET,
        "equal_to_numpy": equal,
        "simulation_seconds": round(seconds, 1),
    }
    if arguments.json:
        print(json.dumps(figures, indent=1))
    else:
        print(
            f"{arguments.width}x{arguments.height} rgb8 through the three stages at "
            f"{arguments.bus} bits: {run.cycles} cycles from the first input beat to the last "
            f"output beat, {run.cycles / pixels:.4f} per input pixel (target ≤ {TARGET}); "
            f"output equal to NumPy: {equal} ({seconds:.0f} s of MyHDL simulation)"
        )
    return 0 if equal and run.cycles / pixels <= TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
