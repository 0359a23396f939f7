"""Software models of the test systems' accelerators (ROS-SW calling convention).

`pass_through` (rfc's generic block) is the hardware pass-through accelerator and `identity`
its reference model; `clear_covariance` is a software-only accelerator.
"""

from dataclasses import replace

import numpy as np

from rfc.lib.passthrough import pass_through

__all__ = ["clear_covariance", "identity", "pass_through"]


def identity(message):
    return message


def clear_covariance(message):
    """PoseWithCovarianceStamped with its covariance zeroed and x doubled."""
    pose = replace(
        message.pose.pose,
        position=replace(message.pose.pose.position, x=2 * message.pose.pose.position.x),
    )
    return replace(message, pose=replace(message.pose, pose=pose, covariance=np.zeros(36)))
