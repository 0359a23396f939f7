"""A MyHDL accelerator fixture for the Python front-end tests: ports annotated with messages.

The block only registers its input (the real Quaternion→Euler accelerator is another issue's);
what the tests need is a genuine MyHDL @block carrying rfc's annotation, and a reference model.
"""

import math

from myhdl import Signal, always_seq, block, intbv

import rfc


def quat_to_euler(x: float, y: float, z: float, w: float) -> tuple[float, float, float]:
    """Reference model: roll, pitch, yaw of a unit quaternion."""
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


@rfc.accelerator(
    inputs={"q": "geometry_msgs/Quaternion"},
    outputs={"euler": "geometry_msgs/Point"},
    reference=quat_to_euler,
)
@block
def QuaternionToEuler(clk, rst, q, euler):  # noqa: N802 (a type name, as in YAML)
    """Registers q.x into euler.x: a stand-in datapath on interface objects."""
    held = Signal(intbv(0)[64:])

    @always_seq(clk.posedge, reset=rst)
    def step():
        held.next = q.x
        euler.x.next = held

    return step
