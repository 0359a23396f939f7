"""The pass-through accelerators of the multi-type system: hardware block and Python model.

`typed_pass_through` is rfc's generic pass-through block on interface objects
(`rfc.lib.passthrough`), one block for Image, LaserScan and TwistStamped alike. `identity` is
its reference model (and, switched to ROS-SW, the software implementation): it returns the
message it is given.
"""

from rfc.lib.passthrough import typed_pass_through

__all__ = ["identity", "typed_pass_through"]


def identity(message):
    """Return the message unchanged."""
    return message
