"""Notes on stderr that commands share: what of the user's input they leave out, and why."""

from __future__ import annotations

import sys
from collections.abc import Iterable
from pathlib import Path


def note_skipped(bag: Path, skipped: Iterable[str]) -> None:
    """Say which topics of the bag are services or actions, not messages, and so left out."""
    for topic in skipped:
        print(
            f"note: {bag}: {topic} is a service or action, not a message; skipped",
            file=sys.stderr,
        )


def note_skipped_topics(bag: Path) -> None:
    """Read the bag's topics and note those left out (see `note_skipped`)."""
    from rfc.messages.rosbags_adapter import skipped_topics

    note_skipped(bag, skipped_topics(bag))
