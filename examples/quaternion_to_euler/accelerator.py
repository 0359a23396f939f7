"""The QuaternionToEuler accelerator as rfc sees it: ROS message ports around the MyHDL core.

`quaternion_to_euler` takes one interface object per message port (docs/accelerators.md):
``q`` holds the geometry_msgs/Quaternion's fields ``q.x`` … ``q.w`` and its handshake
``q.valid``/``q.ready``, ``euler`` the geometry_msgs/Point's. It only hands them to the core
(`quat_to_euler.quat_to_euler`). `quaternion_to_euler_message` is the same computation on ROS
messages — the bit-accurate reference — which runs when the accelerator is switched to ROS-SW,
and which `rfc sim` results are held to.
"""

from __future__ import annotations

from typing import Any

from myhdl import block
from quat_to_euler import quat_to_euler, reference

from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.messages.rosbags_adapter import message_types


@block
def quaternion_to_euler(clk: Any, rst: Any, q: Any, euler: Any) -> Any:
    """geometry_msgs/Quaternion q in, geometry_msgs/Point euler out (x roll, y pitch, z yaw)."""
    return quat_to_euler(
        clk, rst, q.x, q.y, q.z, q.w, q.valid, q.ready,
        euler.x, euler.y, euler.z, euler.valid, euler.ready,
    )  # fmt: skip


def quaternion_to_euler_message(q: Any) -> Any:
    """The bit-accurate reference on a rosbags Quaternion; returns a rosbags Point."""
    roll, pitch, yaw = reference(*(float_to_bits(value) for value in (q.x, q.y, q.z, q.w)))
    point = {"x": bits_to_float(roll), "y": bits_to_float(pitch), "z": bits_to_float(yaw)}
    return message_types("ros2").build("geometry_msgs/msg/Point", point)
