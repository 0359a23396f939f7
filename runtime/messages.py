"""Message objects on the processor side: rosbags (de)serialization from definitions as data.

ROS-SW accelerators take and return rosbags message objects. The runtime plan carries the
definition of every type it uses (each with the types it depends on), so the node builds its
own type store from them and needs neither the compiler nor the build machine's .msg files.
This is the runtime's only use of rosbags.
"""

from __future__ import annotations

from collections.abc import Mapping

from rosbags.serde import SerdeError
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from rfc.messages.codec import FrameError
from rfc.messages.layout_model import Middleware


class MessageObjects:
    """(De)serializes the plan's message types with rosbags.

    Args:
        middleware: Decides the wire format (ROS 1, or ROS 2's CDR with its header).
        definitions: Canonical type name → ``definition`` (its text with its dependencies)
            and ``md5`` (ROS 1's sum of it).
    """

    def __init__(self, middleware: Middleware, definitions: Mapping[str, Mapping[str, str]]):
        self.middleware = middleware
        self.definitions = definitions
        self._store = get_typestore(Stores.EMPTY)
        for name, entry in definitions.items():
            self._store.register(get_types_from_msg(entry["definition"], name))

    def deserialize(self, data: bytes | memoryview, canonical: str) -> object:
        """A message object from its bytes.

        Raises:
            FrameError: The bytes are not a message of the type.
        """
        try:
            if self.middleware is Middleware.ROS2:
                return self._store.deserialize_cdr(data, canonical)
            return self._store.deserialize_ros1(data, canonical)
        except (SerdeError, ValueError, IndexError) as exc:
            raise FrameError("malformed", f"not a {canonical}: {exc}") from None

    def serialize(self, message: object, canonical: str) -> bytes:
        """The bytes of a message object (ROS 2: CDR with its header, little-endian)."""
        if self.middleware is Middleware.ROS2:
            return bytes(self._store.serialize_cdr(message, canonical, little_endian=True))
        return bytes(self._store.serialize_ros1(message, canonical))
