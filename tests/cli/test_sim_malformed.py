"""`rfc sim --send-malformed`: damaged frames end in the logic, counted by reason.

Valid messages serialized by rosbags are mixed in one bag with truncated, extended,
lengthened (beyond the project's maxima) and bit-flipped copies and sent to the simulated logic
(GHDL) of a subscriber → pass-through → publisher system: a Point (fixed-size fields, behind
the drop gate) and a JointState (strings and sequences, behind the frame guard). What comes out
must be exactly what the valid frames give — rosbags' re-serialization of each frame the
reference codec accepts within the maxima, in order — and the account must name every other
frame as dropped in the logic, with the reason its damage implies.
"""

from __future__ import annotations

import json
import random
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from rfc.messages.codec import FrameError, decode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import (
    MessageTypes,
    Middleware,
    message_types,
    read_bag,
    write_bag,
)
from tests.lower.system.systems import PASS_THROUGH, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
POINT, JOINTS = "geometry_msgs/msg/Point", "sensor_msgs/msg/JointState"
#: The project's maxima (small, so that the guard's buffer and lengthened messages stay small).
MAXIMA = Limits(string=12, sequence=5)
#: The reason each kind of damage implies (bit flips may hit a length: any reason).
IMPLIED = {"truncated": "truncated", "extended": "trailing", "lengthened": "maximum"}


def spec_text(middleware: str, width: int, message: str) -> str:
    short = message.replace("/msg/", "/")
    return f"""
project: {{name: Guard, middleware: {middleware}, busWidth: {width}, scheduler: PFP,
          maxima: {{string: {MAXIMA.string}, sequence: {MAXIMA.sequence}}}}}
accelerators:
  - name: Forward
    type: MyHDL
    sources: ./pass.py
    top: pass_through
    interface:
      input: [{{message: {short}}}]
      output: [{{message: {short}}}]
blocks:
  - {{name: sub, type: ROS>accelerator, message: {short}, topic: /in, outgoing: [{{name: acc}}]}}
  - {{name: acc, type: Forward, outgoing: [{{name: pub}}]}}
  - {{name: pub, type: accelerator>ROS, message: {short}, topic: /out}}
"""


def point(rng: random.Random, longer: bool, ros1: bool) -> dict[str, Any]:
    return {"x": rng.uniform(-1e6, 1e6), "y": rng.random(), "z": -rng.random()}


def joints(rng: random.Random, longer: bool, ros1: bool) -> dict[str, Any]:
    """A JointState within the maxima, or (`longer`) with one string or sequence beyond them."""
    count = rng.randrange(0, MAXIMA.sequence + 1)
    names = ["j" * rng.randrange(0, MAXIMA.string + 1) for _ in range(count)]
    frame_id = "base"
    if longer and rng.random() < 0.5:
        frame_id = "f" * (MAXIMA.string + rng.randrange(1, 4))
    elif longer:
        names = names + ["x"] * (MAXIMA.sequence + 1 - count)
    header = {"stamp": {"sec": rng.randrange(1 << 31), "nanosec": 7}, "frame_id": frame_id}
    return {
        "header": {**header, "seq": rng.randrange(1 << 32)} if ros1 else header,
        "name": names,
        "position": np.array([rng.random() for _ in range(count)]),
        "velocity": np.array([], dtype=np.float64),
        "effort": np.array([rng.random() for _ in range(rng.randrange(0, 3))]),
    }


MAKERS = {POINT: point, JOINTS: joints}


def frames_of(types: MessageTypes, message: str, rng: random.Random) -> list[tuple[str, bytes]]:
    """Valid frames and damaged ones, each with how it was made."""
    made = []
    for _ in range(16):
        kind = rng.choice(["valid", "valid", "truncated", "extended", "flipped", "lengthened"])
        longer = kind == "lengthened" and message == JOINTS
        values = MAKERS[message](rng, longer, types.middleware is Middleware.ROS1)
        frame = types.serialize(types.build(message, values), message)
        if kind == "truncated":
            frame = frame[: rng.randrange(0, len(frame))]
        elif kind == "extended":
            frame += rng.randbytes(rng.randrange(1, 12))
        elif kind == "flipped":
            data = bytearray(frame)
            for _ in range(rng.randrange(1, 4)):
                data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
            frame = bytes(data)
        made.append((kind, frame))
    return made


def accepted(types: MessageTypes, message: str, frame: bytes) -> bool:
    """Whether the logic must take the frame: the codec reads it and it is within the maxima."""
    layout = flatten(types, message)
    try:
        values = decode(layout, frame)
    except FrameError:
        return False
    return MAXIMA.beyond(layout, values) is None


SLOW = pytest.mark.slow  # a JointState system takes 10 to 25 s to build and simulate
#: The gate and the guard, each on both middlewares and all three widths (tests/lib/converters/
#: test_malformed.py runs the subscriber itself on every pair).
CASES = [
    ("ROS1", 8, POINT),
    ("ROS2", 32, POINT),
    ("ROS2", 64, POINT),
    pytest.param("ROS2", 8, JOINTS, marks=SLOW),
    pytest.param("ROS1", 32, JOINTS, marks=SLOW),
    pytest.param("ROS1", 64, JOINTS, marks=SLOW),
]


@pytest.mark.parametrize(("middleware", "width", "message"), CASES)
def test_damaged_frames_end_in_the_logic_and_only_valid_ones_come_out(
    tmp_path, middleware, width, message
):
    spec = write_spec(tmp_path, spec_text(middleware, width, message), pass__py=PASS_THROUGH)
    types = message_types(middleware.lower())
    made = frames_of(types, message, random.Random(f"{middleware}{width}{message}"))
    suffix = ".bag" if middleware == "ROS1" else ".mcap"
    bag = tmp_path / f"in{suffix}"
    write_bag(bag, types, {"/in": message}, [("/in", 1000 * i, f) for i, (_, f) in enumerate(made)])
    expected, implied, refused = [], Counter(), 0
    for kind, frame in made:
        if accepted(types, message, frame):
            expected.append(types.serialize(types.deserialize(frame, message), message))
            continue
        refused += 1
        if kind in IMPLIED:
            implied[f"logic:{IMPLIED[kind]}"] += 1
    assert expected  # the mix holds valid frames
    assert refused  # and frames the logic must drop

    out = tmp_path / f"out{suffix}"
    result = run_rfc(
        "sim", spec, "--bag", bag, "--out", out, "--send-malformed", "--depth", "32", "--json",
        cwd=ROOT,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert [m.data for m in read_bag(out, types)] == expected
    assert account["to_logic"] == {"sub": len(made)}
    assert account["from_logic"] == {"pub": len(expected)}
    dropped = Counter({d["reason"]: d["count"] for d in account["dropped"] if d["where"] == "sub"})
    assert sum(dropped.values()) == refused
    assert not implied - dropped  # every damage with an implied reason counted under it
    assert len(account["dropped"]) == len(dropped)  # nothing dropped anywhere else
