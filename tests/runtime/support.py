"""Test systems for the runtime: spec variants written beside their software models."""

from __future__ import annotations

import shutil
from pathlib import Path

from rfc.driver import compile_spec
from rfc.messages.rosbags_adapter import BagMessage, MessageTypes

SYSTEMS = Path(__file__).parent / "systems"


def system_copy(directory: Path, name: str, *replacements: tuple[str, str]) -> Path:
    """Copy a test system (and its Python models) into `directory`, editing its spec text."""
    shutil.copy(SYSTEMS / "passthrough.py", directory / "passthrough.py")
    text = (SYSTEMS / name).read_text()
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    path = directory / name
    path.write_text(text)
    return path


def compiled(directory: Path, name: str, *replacements: tuple[str, str]):
    return compile_spec(system_copy(directory, name, *replacements))


def pose_messages(types: MessageTypes, count: int, topic: str = "/amcl_pose") -> list[BagMessage]:
    """PoseWithCovarianceStamped messages with distinct values, 10 ms apart."""
    name = "geometry_msgs/msg/PoseWithCovarianceStamped"
    messages = []
    for index in range(count):
        tree = {
            "header": {"stamp": {"sec": index, "nanosec": 7 * index}, "frame_id": f"map{index}"},
            "pose": {
                "pose": {
                    "position": {"x": index * 0.5, "y": -1.25, "z": 3.0},
                    "orientation": {"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8},
                },
                "covariance": [float(index + k) for k in range(36)],
            },
        }
        data = types.serialize(types.build(name, tree), name)
        messages.append(BagMessage(topic, name, 1_000_000_000 + index * 10_000_000, data))
    return messages


def vhdl_only_top(design, directory):
    """A top provider whose logic exists only as VHDL (as generated hardware may)."""
    from tests.runtime.echo_top import simulation_top

    top = simulation_top(design, directory)
    return type(
        "VhdlTop", (), {"top": top.top, "sources": top.sources, "bus_width": top.bus_width}
    )()
