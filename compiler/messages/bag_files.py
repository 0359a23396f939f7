"""Telling bag files from other files by their first bytes, before rfc reads or replaces one."""

from __future__ import annotations

from pathlib import Path

from rfc.errors import RfcError
from rfc.messages.rosbags_adapter import Middleware

#: The first bytes of each bag format rosbags writes: ROS 1 bags, MCAP and SQLite (.db3).
BAG_MAGIC = {
    b"#ROSBAG V2.0\n": "a ROS 1 bag",
    b"\x89MCAP0\r\n": "an MCAP bag",
    b"SQLite format 3\x00": "a SQLite (.db3) bag",
}
#: The middleware whose messages each format holds.
_MIDDLEWARE = {
    "a ROS 1 bag": Middleware.ROS1,
    "an MCAP bag": Middleware.ROS2,
    "a SQLite (.db3) bag": Middleware.ROS2,
}


def bag_format(path: Path) -> str | None:
    """What kind of bag `path` is ("a ROS 1 bag", ...), or None when it is not one."""
    try:
        with path.open("rb") as stream:
            head = stream.read(max(len(magic) for magic in BAG_MAGIC))
    except OSError:
        return None
    for magic, kind in BAG_MAGIC.items():
        if head.startswith(magic):
            return kind
    return None


def refuse_to_replace_a_non_bag(path: Path, force: bool) -> None:
    """Raise unless `path` is absent, a bag (a previous output), or `force` says replace it.

    Raises:
        RfcError: `path` is an existing file that is not a bag.
    """
    if force or not path.exists() or path.is_dir() or bag_format(path) is not None:
        return
    raise RfcError(
        f"--out '{path}' exists and is not a bag; refusing to replace it",
        hint="name a new file, or pass --force to replace it",
    )


def check_input_bag(path: Path, middleware: Middleware) -> None:
    """Raise unless the file `path` is a bag of `middleware` (a directory is left to rosbags).

    Raises:
        RfcError: `path` is not a bag, or a bag of the other middleware.
    """
    if not path.is_file():
        return
    kind = bag_format(path)
    if kind is None:
        raise RfcError(
            f"'{path}' is not a bag: it starts with none of the ROS 1 bag, MCAP or SQLite "
            "signatures",
            hint="give a .bag (ROS 1), .mcap or .db3 (ROS 2) file recorded by rosbag or ros2 bag",
        )
    if _MIDDLEWARE[kind] is not middleware:
        raise RfcError(
            f"'{path}' is {kind}, with {_MIDDLEWARE[kind].label} messages, but the project is "
            f"{middleware.label}",
            hint="set the project's middleware to match, or convert the bag with rosbags-convert",
        )
