"""Benchmark: cycles per input pixel of the whole image pipeline system, in a plain testbench.

Builds `examples/image_pipeline/ImagePipeline.yaml` (`rfc build`) and runs its generated logic
in GHDL under the VHDL testbench of `bench_quaternion` (no Python per beat): the DMA side
offers chunks of random rgb8 images of the spec's largest size (40 x 40) back to back and
always takes the results. Every output must equal NumPy's pipeline (the example's reference);
the figure is the cycles from the first input beat to the last output beat over the input
pixels, and the same in the steady state (from the first result to the last, over the pixels
of the images between).

Usage: .venv/bin/python tools/bench_image_system.py [--images N] [--size PIXELS]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "image_pipeline"
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(EXAMPLE))

from bench_quaternion import BEAT, chunk_beats, testbench  # noqa: E402
from image_reference import pipeline, pixels  # noqa: E402

from rfc.messages.rosbags_adapter import message_types  # noqa: E402
from rfc.toolchain.ghdl import simulate  # noqa: E402

IMAGE = "sensor_msgs/msg/Image"


def image_payload(types, rgb: np.ndarray, index: int) -> bytes:
    """One rgb8 image serialized as rosbags does."""
    height, width, _ = rgb.shape
    fields = {
        "header": {"stamp": {"sec": index, "nanosec": 0}, "frame_id": f"cam{index}"},
        "height": height,
        "width": width,
        "encoding": "rgb8",
        "is_bigendian": 0,
        "step": 3 * width,
        "data": rgb.reshape(-1),
    }
    return types.serialize(types.build(IMAGE, fields), IMAGE)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--images", type=int, default=8, help="images back to back")
    parser.add_argument("--size", type=int, default=40, help="rows and columns of each image")
    args = parser.parse_args()
    types = message_types("ros2")
    rng = np.random.default_rng(args.images)
    images = [
        rng.integers(0, 256, size=(args.size, args.size, 3), dtype=np.uint8)
        for _ in range(args.images)
    ]
    beats = [b for i, rgb in enumerate(images) for b in chunk_beats(image_payload(types, rgb, i))]
    with tempfile.TemporaryDirectory(prefix="rfc-bench-image-") as scratch:
        work = Path(scratch)
        build = work / "build"
        built = subprocess.run(
            [sys.executable, "-m", "rfc", "build", str(EXAMPLE / "ImagePipeline.yaml"), "-o",
             str(build)],
            capture_output=True, text=True, cwd=ROOT,
            env={"RFC_USER_CODE_TIMEOUT": "600", **os.environ},
        )  # fmt: skip
        if built.returncode != 0:
            raise SystemExit(f"rfc build failed:\n{built.stderr}")
        files = [build / "hw" / name for name in (build / "hw" / "files.txt").read_text().split()]
        source = work / "bench.vhd"
        limit = 4 * len(beats) + 20_000
        source.write_text(testbench(beats, len(images), files[-1].stem, limit))
        output = simulate([*files, source], "bench", work / "ghdl")
    first_in = next(int(line.split()[1]) for line in output.splitlines() if "FIRST_IN" in line)
    chunks, ends, current = [], [], b""
    for line in output.splitlines():
        if not line.startswith("OUT "):
            continue
        _, cycle, data, keep, last = line.split()
        current += int(data, 16).to_bytes(BEAT, "little")[: bin(int(keep, 16)).count("1")]
        if last == "1":
            chunks.append(current)
            ends.append(int(cycle))
            current = b""
    results = [types.deserialize(chunk[8:], IMAGE) for chunk in chunks]
    pairs = zip(results, images, strict=False)
    equal = len(results) == len(images) and all(
        np.array_equal(pixels(r, 1, "<u4"), pipeline(rgb)) for r, rgb in pairs
    )
    per_pixel = args.size * args.size
    whole = (ends[-1] - first_in) / (per_pixel * len(images))
    steady = (ends[-1] - ends[0]) / (per_pixel * (len(images) - 1))
    print("| images | pixels each | cycles per input pixel, whole run | steady state | results |")
    print("|---:|---:|---:|---:|---|")
    print(
        f"| {len(images)} | {per_pixel} | {whole:.4f} | {steady:.4f} | "
        f"{'all equal' if equal else 'MISMATCH'} |"
    )
    if not equal:
        raise SystemExit("results differ from NumPy's pipeline")


if __name__ == "__main__":
    main()
