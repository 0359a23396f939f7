"""Benchmark: HLS accelerators C-simulated as `rfc sim` runs them (the image pipeline's stages).

Measures the g++ build of the three stages (cold cache, then reused), and the time per frame of
RgbToGray → Downscale → IntegralImage on 640x480 rgb8 images (each stage a call through its
harness over the pipe, the message objects built and read by rfc on the Python side): what
one frame costs `rfc sim`, besides its (de)serialization between the stages.

Usage: .venv/bin/python tools/bench_hls_csim.py [--frames N]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from rfc.driver import compile_spec
from rfc.passes.pipeline import PIPELINE
from rfc.sim.hls_csim import HlsOnProcessor, attach_c_simulations

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "examples" / "image_pipeline" / "ImagePipeline_hls.yaml"
STAGES = ("RgbToGray", "Downscale", "IntegralImage")
IMAGE = "sensor_msgs/msg/Image"


def main() -> None:
    """Print the build times and the time per frame."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=20)
    arguments = parser.parse_args()
    design = compile_spec(SPEC, pipeline=(HlsOnProcessor(), *PIPELINE))
    with tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        attach_c_simulations(design, Path(cache))
        cold = time.perf_counter() - start
        start = time.perf_counter()
        built = attach_c_simulations(design, Path(cache))
        warm = time.perf_counter() - start
        stages = [built.accelerator(name).reference_function for name in STAGES]
        types = stages[0].types
        rng = np.random.default_rng(1)
        pixels = rng.integers(0, 256, size=(480, 640, 3), dtype=np.uint8)
        tree = {
            "header": {"stamp": {"sec": 1, "nanosec": 2}, "frame_id": "camera"},
            "height": 480,
            "width": 640,
            "encoding": "rgb8",
            "step": 3 * 640,
            "data": pixels.reshape(-1),
        }
        message = types.build(IMAGE, tree)
        times = []
        for _ in range(arguments.frames):
            start = time.perf_counter()
            result = message
            for stage in stages:
                result = stage(result)
            times.append(time.perf_counter() - start)
    print(f"g++ build of the three stages: {cold:.2f} s cold, {warm * 1000:.0f} ms cached")
    print(
        f"640x480 frame through the three stages: median {np.median(times) * 1000:.1f} ms "
        f"(min {min(times) * 1000:.1f} ms) over {arguments.frames} frames"
    )


if __name__ == "__main__":
    main()
