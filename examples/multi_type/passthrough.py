"""The pass-through accelerators of the multi-type system, as Python models.

`identity` is the reference model (and, switched to ROS-SW, the software implementation) of
each pass-through accelerator: it returns the message it is given.
"""


def identity(message):
    """Return the message unchanged."""
    return message
