"""The image pipeline of ImagePipeline.yaml, written in Python: the same system, the same IR."""

import rfc

IMAGE = "sensor_msgs/Image"
USED = ["height", "width", "data"]

RgbToGray = rfc.external_accelerator(
    "RgbToGray",
    kind="HLS",
    sources="./rgb_to_gray.cpp",
    inputs={"rgb": rfc.port(IMAGE, include=USED)},
    outputs={"gray": IMAGE},
)
Downscale = rfc.external_accelerator(
    "Downscale",
    kind="HLS",
    sources="./downscale.cpp",
    inputs={"full": rfc.port(IMAGE, include=USED)},
    outputs={"small": IMAGE},
)
IntegralImage = rfc.external_accelerator(
    "IntegralImage",
    kind="HLS",
    sources="./integral_image.cpp",
    inputs={"image": rfc.port(IMAGE, include=USED)},
    outputs={"integral": IMAGE},
)

project = rfc.Project(
    "ImagePipeline",
    fpga_part="xc7z020clg400-1",
    middleware="ROS2",
    distro="humble",
    bus_width=64,
    clock_mhz=100,
    scheduler="LRU",
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
