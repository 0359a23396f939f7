"""The pass-through accelerators of the multi-type system: hardware block and Python model.

`pass_through` is rfc's generic pass-through block (`rfc.lib.passthrough`), one block for
Image, LaserScan and TwistStamped alike. `identity` is its reference model (and, switched to
ROS-SW, the software implementation): it returns the message it is given.
"""

from rfc.lib.passthrough import pass_through

__all__ = ["identity", "pass_through"]


def identity(message):
    """Return the message unchanged."""
    return message
