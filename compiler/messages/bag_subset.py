"""The part of a bag a replay asks for: some topics, the first N messages, as a new bag."""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from pathlib import Path

from rfc.messages.rosbags_adapter import MessageTypes, Middleware, bag_topics, read_bag, write_bag


def write_subset(
    bag: Path, types: MessageTypes, topics: Mapping[str, str], limit: int | None, folder: Path
) -> Path:
    """Write the first `limit` messages (all when None) of `topics` in `bag` to a bag in `folder`.

    The messages keep their topics, time stamps and bytes, so a replay of the subset is the
    start of the replay of the whole bag.

    Args:
        bag: The recorded bag.
        types: Definitions of the bag's messages.
        topics: The bag's topics to keep (keys; values are ignored).
        limit: How many messages to keep, in time order over all kept topics.
        folder: Where the subset goes.

    Returns:
        The subset bag (ROS 1 ``.bag`` or ROS 2 ``.mcap``, as the messages are).
    """
    suffix = ".bag" if types.middleware is Middleware.ROS1 else ".mcap"
    target = folder / f"subset{suffix}"
    kinds = bag_topics(bag, types)
    messages = read_bag(bag, types, sorted(topics))
    write_bag(
        target,
        types,
        {topic: kinds[topic] for topic in topics},
        ((m.topic, m.timestamp_ns, m.data) for m in itertools.islice(messages, limit)),
    )
    return target
