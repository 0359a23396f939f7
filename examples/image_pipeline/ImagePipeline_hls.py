"""The image pipeline of ImagePipeline_hls.yaml, written in Python: the same system, the same IR."""

import rfc

IMAGE = "sensor_msgs/Image"


def image_stage(name: str, source: str, port_in: str, port_out: str):
    """An HLS stage taking an image (its header, size and pixels) and giving one."""
    return rfc.external_accelerator(
        name,
        kind="HLS",
        sources=source,
        inputs={port_in: rfc.port(IMAGE, include=["header", "height", "width", "data"])},
        outputs={port_out: IMAGE},
    )


RgbToGray = image_stage("RgbToGray", "./rgb_to_gray.cpp", "rgb", "gray")
Downscale = image_stage("Downscale", "./downscale.cpp", "full", "small")
IntegralImage = image_stage("IntegralImage", "./integral_image.cpp", "image", "integral")

project = rfc.Project(
    "ImagePipeline",
    fpga_part="xc7z020clg400-1",
    middleware="ROS2",
    distro="humble",
    bus_width=64,
    clock_mhz=100,
    scheduler="LRU",
    # full-HD RGB frames (1920 x 1080 x 3 bytes of data), short names and encodings
    maxima={"string": 64, "fields": {"data": 6220800}},
)
camera = project.subscriber(
    "Camera_sub", IMAGE, topic="/camera/image_raw", period="33 ms", max_bytes=6220900
)
gray = project.accelerator("Gray_acc", RgbToGray)
small = project.accelerator("Downscale_acc", Downscale)
integral = project.accelerator("Integral_acc", IntegralImage)
publisher = project.publisher(
    "Integral_pub", IMAGE, topic="/camera/integral", period="33 ms", max_bytes=1228900
)

frame = ["header", "height", "width", "data"]
camera.include(*frame) >> gray
gray.include(*frame) >> small
small.include(*frame) >> integral
integral.exclude("is_bigendian") >> publisher
