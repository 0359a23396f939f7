"""The QuaternionToEuler accelerators as rfc sees them: ROS message ports around the MyHDL cores.

Each takes one interface object per message port (docs/accelerators.md): ``q`` holds the
geometry_msgs/Quaternion's fields ``q.x`` … ``q.w`` and its handshake ``q.valid``/``q.ready``,
``euler`` the geometry_msgs/Point's. `quaternion_to_euler` is the fast one (a quaternion every
cycle, `quat_to_euler_pipelined`); `quaternion_to_euler_iterative` the small one (one
quaternion at a time, `quat_to_euler`). The ``*_message`` functions are the same computations
on ROS messages — the bit-accurate references — which run when the accelerator is switched to
ROS-SW, and which `rfc sim` results are held to.
"""

from __future__ import annotations

from typing import Any

from myhdl import block
from quat_to_euler import ITERATIVE, PIPELINED, Precision, quat_to_euler, reference
from quat_to_euler_pipelined import quat_to_euler_pipelined

from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.messages.rosbags_adapter import message_types


@block
def quaternion_to_euler(clk: Any, rst: Any, q: Any, euler: Any) -> Any:
    """geometry_msgs/Quaternion q in, geometry_msgs/Point euler out (x roll, y pitch, z yaw)."""
    return quat_to_euler_pipelined(
        clk, rst, q.x, q.y, q.z, q.w, q.valid, q.ready,
        euler.x, euler.y, euler.z, euler.valid, euler.ready,
    )  # fmt: skip


# The same wrapper around the other core: a spec names its accelerator's top function.
@block
def quaternion_to_euler_iterative(clk: Any, rst: Any, q: Any, euler: Any) -> Any:
    """As `quaternion_to_euler`, one quaternion at a time in under a third of the logic."""
    return quat_to_euler(
        clk, rst, q.x, q.y, q.z, q.w, q.valid, q.ready,
        euler.x, euler.y, euler.z, euler.valid, euler.ready,
    )  # fmt: skip


def _point(q: Any, precision: Precision) -> Any:
    bits = (float_to_bits(value) for value in (q.x, q.y, q.z, q.w))
    roll, pitch, yaw = reference(*bits, precision)
    point = {"x": bits_to_float(roll), "y": bits_to_float(pitch), "z": bits_to_float(yaw)}
    return message_types("ros2").build("geometry_msgs/msg/Point", point)


def quaternion_to_euler_message(q: Any) -> Any:
    """The fast accelerator's bit-accurate reference on a rosbags Quaternion: a rosbags Point."""
    return _point(q, PIPELINED)


def quaternion_to_euler_iterative_message(q: Any) -> Any:
    """The iterative accelerator's bit-accurate reference (rosbags Quaternion → Point)."""
    return _point(q, ITERATIVE)
