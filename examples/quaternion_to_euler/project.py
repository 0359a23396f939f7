"""The quaternion example (paper Listing 1) in Python: the same system as project.yaml."""

from accelerator import quaternion_to_euler, quaternion_to_euler_message

import rfc

QuaternionToEuler = rfc.accelerator(
    inputs={"q": "geometry_msgs/Quaternion"},
    outputs={"euler": "geometry_msgs/Point"},
    reference=quaternion_to_euler_message,
    name="QuaternionToEuler",
)(quaternion_to_euler)

project = rfc.Project(
    "QuaternionToEuler",
    fpga_part="xc7z020clg400-1",
    middleware="ROS2",
    distro="humble",
    bus_width=64,
    clock_mhz=100,
    scheduler="LRU",
)
orientation = project.subscriber(
    "orientation_sub", "geometry_msgs/Quaternion", topic="/imu/orientation"
)
angles = project.accelerator("quat_to_euler", QuaternionToEuler)
euler = project.publisher("euler_pub", "geometry_msgs/Point", topic="/imu/euler")

orientation >> angles >> euler
