"""What every pass shares: the `Pass` protocol and the message types of a design."""

from __future__ import annotations

from typing import ClassVar, Protocol

from rfc.ir.model import Design, ProjectSettings
from rfc.messages.rosbags_adapter import MessageTypes, message_types


class Pass(Protocol):
    """A named step of the pipeline: a frozen dataclass with one `apply`.

    A pass never writes files and never mutates its input; it returns a new design one stage
    further on, or raises `RfcError` pointing at the spec element at fault.
    """

    name: ClassVar[str]

    def apply(self, design: Design) -> Design:
        """Return the design transformed by this pass."""
        ...


def types_of(project: ProjectSettings) -> MessageTypes:
    """The message definitions a project's types resolve in (shared, built once)."""
    return message_types(
        project.middleware, project.distro, tuple(str(p) for p in project.msg_paths)
    )
