"""quat_myhdl.yaml in Python: the MyHDL accelerator carries its own annotation."""

from quat_model import QuaternionToEuler

import rfc

project = rfc.Project(
    "RotationConverterNode",
    fpga_part="xc7z020clg400-1",
    middleware="ROS2",
    distro="humble",
    bus_width=64,
    clock_mhz=100,
    scheduler="LOEDF",
)
imu = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion", topic="/imu/orientation")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher(
    "Euler_pub", "geometry_msgs/Point", topic="/euler", period=1000, deadline="10 us"
)
imu >> acc["q"] >> pub
