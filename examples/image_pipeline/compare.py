"""Compare the integral images of `rfc sim` with NumPy's: pixel for pixel, header for header.

    python compare.py images.mcap integral.mcap

Each output must be the NumPy pipeline (gray, downscale, integral) of its input, as a 32SC1
image of the downscaled size with step 4·width, and keep the input's stamp and frame_id.
Exit status 1 when one is not.
"""

from __future__ import annotations

import sys

from image_reference import pipeline, pixels

from rfc.messages.rosbags_adapter import message_types, read_bag


def messages(bag: str) -> list:
    """The messages of a ROS 2 bag, deserialized."""
    types = message_types("ros2")
    return [types.deserialize(m.data, m.type_name) for m in read_bag(bag, types)]


def differences(image: object, integral: object) -> list[str]:
    """What differs between `integral` and the NumPy pipeline of `image` (nothing: [])."""
    want = pipeline(pixels(image, 3))
    found = []
    if (integral.height, integral.width) != want.shape:
        found.append(f"size {integral.height}x{integral.width}, expected {want.shape}")
    if integral.encoding != "32SC1" or integral.step != 4 * want.shape[1]:
        found.append(f"encoding {integral.encoding!r} step {integral.step}")
    if bytes(integral.data) != want.tobytes():
        found.append("pixels differ")
    stamps = [(m.header.stamp.sec, m.header.stamp.nanosec, m.header.frame_id)
              for m in (image, integral)]  # fmt: skip
    if stamps[0] != stamps[1]:
        found.append(f"header {stamps[1]}, expected {stamps[0]}")
    return found


def main() -> int:
    """Print the comparison; return the exit status."""
    images, integrals = messages(sys.argv[1]), messages(sys.argv[2])
    if len(images) != len(integrals):
        print(f"{len(images)} images in, {len(integrals)} integral images out")
        return 1
    equal = 0
    for index, (image, integral) in enumerate(zip(images, integrals, strict=True)):
        found = differences(image, integral)
        for difference in found:
            print(f"image {index} ({image.height}x{image.width}): {difference}")
        equal += not found
    print(f"{equal} of {len(images)} integral images equal to NumPy's")
    return 0 if equal == len(images) else 1


if __name__ == "__main__":
    sys.exit(main())
