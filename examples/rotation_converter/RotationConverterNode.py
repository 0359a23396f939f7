"""The paper's Listing 1 in Python: the same system as RotationConverterNode.yaml."""

import rfc

QuaternionToEuler = rfc.external_accelerator(
    "QuaternionToEuler",
    kind="HLS",
    sources="./QuaternionToEulerConverter.cpp",
    inputs="geometry_msgs/Quaternion",
    outputs="geometry_msgs/Point",
)

project = rfc.Project("RotationConverterNode", fpga_part="xc7z020clg400-1", middleware="ROS")
quaternion_sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
accelerator = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
euler_pub = project.publisher("Euler_pub", "geometry_msgs/Point")

quaternion_sub >> accelerator >> euler_pub
