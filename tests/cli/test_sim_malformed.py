"""`rfc sim --send-malformed`: damaged frames end in the logic, counted by reason.

Valid Point messages (serialized by rosbags) are mixed in one bag with truncated, extended and
bit-flipped copies and sent to the simulated logic (GHDL) of a subscriber → pass-through →
publisher system. What comes out must be exactly what the valid frames give — rosbags'
re-serialization of each frame the reference codec accepts, in order — and the account must
name every other frame as dropped in the logic, with its reason.
"""

from __future__ import annotations

import json
import random
from collections import Counter
from pathlib import Path

import pytest

from rfc.messages.codec import FrameError, decode
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.lower.system.systems import PASS_THROUGH, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
POINT = "geometry_msgs/msg/Point"
#: The reason the logic must give for each kind of damage the codec refuses.
REASONS = {"truncated": "truncated", "extended": "trailing", "flipped": "encoding"}


def spec_text(middleware: str, width: int) -> str:
    return f"""
project: {{name: Guard, middleware: {middleware}, busWidth: {width}, scheduler: PFP}}
accelerators:
  - name: PassPoint
    type: MyHDL
    sources: ./pass.py
    top: pass_through
    interface:
      input: [{{message: geometry_msgs/Point}}]
      output: [{{message: geometry_msgs/Point}}]
blocks:
  - {{name: point_sub, type: ROS>accelerator, message: geometry_msgs/Point, topic: /p,
     outgoing: [{{name: acc}}]}}
  - {{name: acc, type: PassPoint, outgoing: [{{name: point_pub}}]}}
  - {{name: point_pub, type: accelerator>ROS, message: geometry_msgs/Point, topic: /q}}
"""


def damaged(frame: bytes, rng: random.Random) -> tuple[str, bytes]:
    """A copy of `frame` truncated, extended or with bits flipped, and which."""
    kind = rng.choice(sorted(REASONS))
    if kind == "truncated":
        return kind, frame[: rng.randrange(0, len(frame))]
    if kind == "extended":
        return kind, frame + rng.randbytes(rng.randrange(1, 12))
    data = bytearray(frame)
    for _ in range(rng.randrange(1, 4)):
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    return kind, bytes(data)


@pytest.mark.parametrize(
    ("middleware", "width", "suffix"),
    [
        ("ROS1", 8, ".bag"),
        ("ROS1", 32, ".bag"),
        ("ROS1", 64, ".bag"),
        ("ROS2", 8, ".mcap"),
        ("ROS2", 32, ".mcap"),
        ("ROS2", 64, ".mcap"),
    ],
)
def test_damaged_frames_end_in_the_logic_and_only_valid_ones_come_out(
    tmp_path, middleware, width, suffix
):
    spec = write_spec(tmp_path, spec_text(middleware, width), pass__py=PASS_THROUGH)
    types = message_types(middleware.lower())
    layout = flatten(types, POINT)
    rng = random.Random(f"{middleware}{width}")
    frames, kinds = [], []
    for _ in range(24):
        values = {"x": rng.uniform(-1e6, 1e6), "y": rng.random(), "z": -rng.random()}
        frame = types.serialize(types.build(POINT, values), POINT)
        kind, frame = ("valid", frame) if rng.random() < 0.4 else damaged(frame, rng)
        frames.append(frame)
        kinds.append(kind)
    bag = tmp_path / f"in{suffix}"
    write_bag(bag, types, {"/p": POINT}, [("/p", 1000 * i, f) for i, f in enumerate(frames)])
    expected, drops = [], Counter()
    for kind, frame in zip(kinds, frames, strict=True):
        try:
            decode(layout, frame)
        except FrameError:
            drops[f"logic:{REASONS[kind]}"] += 1
            continue
        expected.append(types.serialize(types.deserialize(frame, POINT), POINT))
    assert expected  # the mix holds valid frames
    assert drops  # and frames the logic must drop

    out = tmp_path / f"out{suffix}"
    result = run_rfc(
        "sim", spec, "--bag", bag, "--out", out, "--send-malformed", "--depth", "32", "--json",
        cwd=ROOT,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert [m.data for m in read_bag(out, types)] == expected
    assert account["to_logic"] == {"point_sub": len(frames)}
    assert account["from_logic"] == {"point_pub": len(expected)}
    dropped = {(d["where"], d["reason"]): d["count"] for d in account["dropped"]}
    assert dropped == {("point_sub", reason): count for reason, count in drops.items()}
    assert len(frames) == account["from_logic"]["point_pub"] + sum(dropped.values())
