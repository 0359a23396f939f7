"""pose_mixed.yaml in Python: ROS-SW functions given as callables (the switch is one keyword)."""

from passthrough import clear_covariance, identity

import rfc

POSE = "geometry_msgs/PoseWithCovarianceStamped"
PASS_KIND = "MyHDL"

PassPose = rfc.external_accelerator(
    "PassPose",
    kind=PASS_KIND,
    sources="./passthrough.py",
    inputs=POSE,
    outputs=POSE,
    reference=identity,
)
ClearCovariance = rfc.external_accelerator(
    "ClearCovariance",
    kind="ROS-SW",
    sources="./passthrough.py",
    inputs=POSE,
    outputs=POSE,
    reference=clear_covariance,
)

project = rfc.Project("PoseMixed", bus_width=64, scheduler="LRU")
pose_sub = project.subscriber("Pose_sub", POSE, topic="/amcl_pose")
first = project.accelerator("Pass", PassPose)
clear = project.accelerator("Clear", ClearCovariance)
second = project.accelerator("Pass2", PassPose)
pose_pub = project.publisher("Pose_pub", POSE, topic="/pose_cleared")
pose_sub >> first >> clear >> second >> pose_pub
