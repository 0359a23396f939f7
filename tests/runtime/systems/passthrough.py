"""Software models of the test systems' accelerators (ROS-SW calling convention).

`identity` is the reference model of the hardware pass-through accelerators (the echo fixture
top-level implements them in the logic); `clear_covariance` is a software-only accelerator.
"""

from dataclasses import replace

import numpy as np


def identity(message):
    return message


def clear_covariance(message):
    """PoseWithCovarianceStamped with its covariance zeroed and x doubled."""
    pose = replace(
        message.pose.pose,
        position=replace(message.pose.pose.position, x=2 * message.pose.pose.position.x),
    )
    return replace(message, pose=replace(message.pose, pose=pose, covariance=np.zeros(36)))
