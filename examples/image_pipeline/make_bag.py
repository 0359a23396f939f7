"""An input bag for the image pipeline: random rgb8 images of varying sizes on /camera/image_raw.

    python make_bag.py images.mcap [--count 4] [--seed 7]

Sizes vary from message to message, odd widths and heights included (Downscale drops the odd
last row and column); each image has its own stamp and frame_id, which every stage keeps.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types, write_bag

TOPIC = "/camera/image_raw"
IMAGE = "sensor_msgs/msg/Image"


def random_images(count: int, seed: int) -> list[np.ndarray]:
    """Random rgb8 images (height by width by 3 bytes): 1 to 30 rows of 1 to 40 pixels."""
    rng = np.random.default_rng(seed)
    sizes = zip(rng.integers(1, 31, size=count), rng.integers(1, 41, size=count), strict=True)
    return [rng.integers(0, 256, size=(h, w, 3), dtype=np.uint8) for h, w in sizes]


def write_images(out: Path, images: list[np.ndarray]) -> None:
    """Write the images as sensor_msgs/Image messages, 1 ms apart, stamped and framed each."""
    types = message_types("ros2")
    messages = []
    for index, pixels in enumerate(images):
        height, width, _ = pixels.shape
        image = {
            "header": {"stamp": {"sec": index, "nanosec": 1000 * index}, "frame_id": f"cam{index}"},
            "height": height,
            "width": width,
            "encoding": "rgb8",
            "is_bigendian": 0,
            "step": 3 * width,
            "data": pixels.reshape(-1),
        }
        data = types.serialize(types.build(IMAGE, image), IMAGE)
        messages.append((TOPIC, 1_000_000 * (index + 1), data))
    write_bag(out, types, {TOPIC: IMAGE}, messages)


def main() -> None:
    """Command line: see the module docstring."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--count", type=int, default=4)
    parser.add_argument("--seed", type=int, default=7)
    arguments = parser.parse_args()
    write_images(arguments.out, random_images(arguments.count, arguments.seed))
    print(f"{arguments.count} images on {TOPIC} in {arguments.out}")


if __name__ == "__main__":
    main()
