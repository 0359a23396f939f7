"""The image pipeline of ImagePipeline.yaml, written in Python: the same system, the same IR.

Its three stages are the MyHDL accelerators of stages.py, in the logic; ImagePipeline_hls.py is
the same system with the HLS stages.
"""

from image_reference import (
    downscale_reference,
    integral_image_reference,
    rgb_to_gray_reference,
)

import rfc

IMAGE = "sensor_msgs/Image"


def image_stage(name: str, top: str, port_in: str, port_out: str, reference):
    """A MyHDL stage of stages.py taking an image (its header, size and pixels) and giving one."""
    return rfc.external_accelerator(
        name,
        kind="MyHDL",
        sources="./stages.py",
        top=top,
        inputs={port_in: rfc.port(IMAGE, include=["header", "height", "width", "data"])},
        outputs={port_out: IMAGE},
        reference=reference,
    )


RgbToGray = image_stage("RgbToGray", "rgb_to_gray", "rgb", "gray", rgb_to_gray_reference)
Downscale = image_stage("Downscale", "downscale", "full", "small", downscale_reference)
IntegralImage = image_stage(
    "IntegralImage", "integral_image", "image", "integral", integral_image_reference
)

project = rfc.Project(
    "ImagePipeline",
    fpga_part="xc7z020clg400-1",
    middleware="ROS2",
    distro="humble",
    bus_width=64,
    clock_mhz=100,
    scheduler="LRU",
    # full-HD RGB frames (1920 x 1080 x 3 bytes of data), short names and encodings; the stages
    # are record-first, so the publisher streams the pixels through (docs/accelerators.md)
    maxima={"string": 64, "fields": {"data": 6220800}},
)
camera = project.subscriber(
    "Camera_sub", IMAGE, topic="/camera/image_raw", period="33 ms", max_bytes=6221000
)
gray = project.accelerator("Gray_acc", RgbToGray)
small = project.accelerator("Downscale_acc", Downscale)
integral = project.accelerator("Integral_acc", IntegralImage)
publisher = project.publisher(
    "Integral_pub", IMAGE, topic="/camera/integral", period="33 ms", max_bytes=2073800
)

frame = ["header", "height", "width", "data"]
camera.include(*frame) >> gray
gray.include(*frame) >> small
small.include(*frame) >> integral
integral.exclude("is_bigendian") >> publisher
