"""The QuaternionToEuler accelerator as rfc sees it: ROS message ports around the MyHDL core.

`quaternion_to_euler` follows rfc's convention for MyHDL accelerators (docs/accelerators.md):
``clk`` and ``rst``, then per input port its fields named ``<port>_<field>`` with
``<port>_valid``/``<port>_ready``, and the same for each output port. It only renames the
core's ports (`quat_to_euler.quat_to_euler`). `quaternion_to_euler_message` is the same
computation on ROS messages — the bit-accurate reference — which runs when the accelerator is
switched to ROS-SW, and which `rfc sim` results are held to.
"""

from __future__ import annotations

from typing import Any

from myhdl import block
from quat_to_euler import quat_to_euler, reference

from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.messages.rosbags_adapter import message_types


@block
def quaternion_to_euler(
    clk: Any,
    rst: Any,
    q_x: Any,
    q_y: Any,
    q_z: Any,
    q_w: Any,
    q_valid: Any,
    q_ready: Any,
    euler_x: Any,
    euler_y: Any,
    euler_z: Any,
    euler_valid: Any,
    euler_ready: Any,
) -> Any:
    """geometry_msgs/Quaternion q in, geometry_msgs/Point euler out (x roll, y pitch, z yaw)."""
    return quat_to_euler(
        clk, rst, q_x, q_y, q_z, q_w, q_valid, q_ready,
        euler_x, euler_y, euler_z, euler_valid, euler_ready,
    )  # fmt: skip


def quaternion_to_euler_message(q: Any) -> Any:
    """The bit-accurate reference on a rosbags Quaternion; returns a rosbags Point."""
    roll, pitch, yaw = reference(*(float_to_bits(value) for value in (q.x, q.y, q.z, q.w)))
    point = {"x": bits_to_float(roll), "y": bits_to_float(pitch), "z": bits_to_float(yaw)}
    return message_types("ros2").build("geometry_msgs/msg/Point", point)
