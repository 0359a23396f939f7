"""What a connection carries, applied in software: unselected fields take their defaults.

In the logic, a subscriber presents only the selected fields and a publisher sends defaults
(zero, false, empty) for the fields nobody drives. When a connection runs on the processor
(into or out of a ROS-SW accelerator), the runtime gives the message the same shape, so that
switching an accelerator between hardware and software changes nothing downstream.
"""

from __future__ import annotations

from typing import Any

from rfc.messages.codec import Values, decode, default_values, encode
from rfc.messages.layout_model import Layout


def selects_everything(layout: Layout) -> bool:
    """Whether every leaf is selected (the frame then passes unchanged)."""
    return all(
        field.selected and (field.element is None or selects_everything(field.element))
        for field in layout.fields
    )


class Shaper:
    """Resets the unselected fields of frames of one layout to their defaults.

    Args:
        layout: The layout of a port, its selection marking what the connection carries.

    Raises:
        FrameError: (from `shape`) The frame is not a valid message of the layout.
    """

    def __init__(self, layout: Layout) -> None:
        self.layout = layout
        self.identity = selects_everything(layout)

    def shape(self, frame: bytes) -> bytes:
        """Check the frame and return it with only the selected fields kept."""
        values = decode(self.layout, frame)
        if self.identity:
            return frame
        return encode(self.layout, _keep_selected(self.layout, values))


def _keep_selected(layout: Layout, values: Values) -> Values:
    defaults = default_values(layout)
    kept: dict[str, Any] = {}
    for field in layout.fields:
        value = values[field.path]
        if not field.selected:
            kept[field.path] = defaults[field.path]
        elif field.element is not None:
            kept[field.path] = [_keep_selected(field.element, item) for item in value]
        else:
            kept[field.path] = value
    return kept
