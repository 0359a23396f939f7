"""Campaign: malformed frames end in the logic, on both middlewares, three bus widths, five types.

Each round builds a subscriber → pass-through → publisher system for one (middleware, bus width,
message type) and replays through the simulated logic (`rfc sim --send-malformed --json`, a
fresh process) one bag of random messages, some left valid and the others truncated, extended,
lengthened beyond the project's maxima, given another CDR encapsulation, or bit-flipped. The
oracles are not rfc's: rosbags re-serializes every frame the reference codec accepts within the
maxima, and those must be exactly what comes out, in order; the logic's drop counters (read
through the status chunk, docs/protocol.md) must account for every other frame, each damage
whose reason is certain under that reason (a bit flip may give any). The suite keeps its bounded
version (tests/cli/test_sim_malformed.py); this runs rounds until the time is up and prints
cases tried and handled, by kind of damage and by round.

Usage:
    .venv/bin/python tools/fuzz_frames.py [--minutes M] [--frames N] [--seed S]
"""

from __future__ import annotations

import argparse
import itertools
import json
import random
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from rfc.messages.codec import FrameError, decode, encode
from rfc.messages.layout import FieldKind, Layout, flatten
from rfc.messages.layout_model import PRIMITIVE_DTYPES
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import (
    MessageTypes,
    Middleware,
    message_types,
    read_bag,
    write_bag,
)

#: Types with strings, sequences of primitives and of strings, fixed arrays, and none of them.
MESSAGES = (
    "sensor_msgs/msg/JointState",
    "sensor_msgs/msg/LaserScan",
    "sensor_msgs/msg/Imu",
    "std_msgs/msg/String",
    "geometry_msgs/msg/Point",
)
MIDDLEWARES = ("ROS1", "ROS2")
WIDTHS = (8, 32, 64)
#: Small maxima: the guards' buffers stay small and lengthened messages short.
MAXIMA = Limits(string=12, sequence=5)
KINDS = ("valid", "truncated", "extended", "lengthened", "encoding", "flipped")
#: The reason each damage implies when the frame is refused (a bit flip: any).
IMPLIED = {
    "truncated": "truncated",
    "extended": "trailing",
    "lengthened": "maximum",
    "encoding": "encoding",
}
#: Seconds one `rfc sim` may take (build, GHDL analysis and simulation).
ROUND_TIMEOUT = 600

SPEC = """
project: {{name: Fuzz, middleware: {middleware}, busWidth: {width}, scheduler: PFP,
          maxima: {{string: {string}, sequence: {sequence}}}}}
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


def random_primitive(rng: random.Random, name: str) -> Any:
    """A value of ROS primitive type `name` (finite floats, any integer of its range)."""
    dtype = PRIMITIVE_DTYPES[name]
    if dtype.kind == "b":
        return rng.random() < 0.5
    if dtype.kind == "f":
        return float(dtype.type(rng.uniform(-1e6, 1e6)))
    info = np.iinfo(dtype)
    return rng.randrange(int(info.min), int(info.max) + 1)


def random_values(layout: Layout, rng: random.Random, longer: bool) -> dict[str, Any]:
    """Random values within the maxima, or (`longer`) one string or sequence beyond them."""
    values: dict[str, Any] = {}
    variable = [f.path for f in layout.fields if f.kind is not FieldKind.PRIMITIVE]
    beyond = rng.choice(variable) if longer and variable else None
    for field in layout.fields:
        if field.kind is FieldKind.PRIMITIVE:
            values[field.path] = random_primitive(rng, field.element_type)
            continue
        bound = MAXIMA.string if field.kind is FieldKind.STRING else MAXIMA.sequence
        count = bound + rng.randrange(1, 4) if field.path == beyond else rng.randrange(bound + 1)
        if field.kind is FieldKind.STRING:
            values[field.path] = "".join(rng.choice("abcxyz_/") for _ in range(count))
        elif field.element_type == "string":
            values[field.path] = ["s" * rng.randrange(MAXIMA.string + 1) for _ in range(count)]
        else:
            dtype = PRIMITIVE_DTYPES[field.element_type]
            items = [random_primitive(rng, field.element_type) for _ in range(count)]
            values[field.path] = np.array(items, dtype=dtype)
    return values


def damaged(frame: bytes, kind: str, ros2: bool, rng: random.Random) -> bytes:
    """The frame with the damage of `kind` (lengthened frames are made so, not damaged)."""
    if kind == "truncated":
        return frame[: rng.randrange(len(frame))]
    if kind == "extended":
        return frame + rng.randbytes(rng.randrange(1, 12))
    if kind == "encoding" and ros2:
        return rng.choice([b"\x00\x00", b"\x00\x02", b"\x00\x03"]) + frame[2:]
    if kind == "flipped":
        data = bytearray(frame)
        for _ in range(rng.randrange(1, 4)):
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        return bytes(data)
    return frame


def accepted(layout: Layout, frame: bytes) -> bool:
    """Whether the logic must pass the frame on: the codec reads it, within the maxima."""
    try:
        values = decode(layout, frame)
    except FrameError:
        return False
    return MAXIMA.beyond(layout, values) is None


def made_frames(
    types: MessageTypes, layout: Layout, message: str, frames: int, rng: random.Random
) -> list[tuple[str, bytes]]:
    """Random frames of `message`, each with the kind of damage it got."""
    ros2 = types.middleware is Middleware.ROS2
    kinds = [k for k in KINDS if ros2 or k != "encoding"]
    made = []
    for _ in range(frames):
        kind = rng.choice(["valid", *kinds])  # about one frame in three valid
        values = random_values(layout, rng, longer=kind == "lengthened")
        frame = types.serialize(types.deserialize(encode(layout, values), message), message)
        made.append((kind, damaged(frame, kind, ros2, rng)))
    return made


def run_round(
    folder: Path, middleware: str, width: int, message: str, frames: int, rng: random.Random
) -> tuple[bool, Counter[str], str]:
    """One system, one bag: whether everything matched, the frames by kind, and what did not."""
    folder.mkdir(parents=True)
    types: MessageTypes = message_types(middleware.lower())
    layout = flatten(types, message)
    ros2 = middleware == "ROS2"
    made = made_frames(types, layout, message, frames, rng)
    expected, implied, refused, flipped = [], Counter(), 0, 0
    for kind, frame in made:
        if accepted(layout, frame):
            expected.append(types.serialize(types.deserialize(frame, message), message))
            continue
        refused += 1
        if kind in IMPLIED:
            implied[f"logic:{IMPLIED[kind]}"] += 1
        else:
            flipped += 1
    short = message.replace("/msg/", "/")
    spec = folder / "spec.yaml"
    spec.write_text(
        SPEC.format(middleware=middleware, width=width, short=short,
                    string=MAXIMA.string, sequence=MAXIMA.sequence)
    )  # fmt: skip
    (folder / "pass.py").write_text("from rfc.lib.passthrough import pass_through\n")
    bag = folder / ("in.bag" if not ros2 else "in.mcap")
    write_bag(bag, types, {"/in": message}, [("/in", 1000 * i, f) for i, (_, f) in enumerate(made)])
    out = folder / ("out.bag" if not ros2 else "out.mcap")
    command = [sys.executable, "-m", "rfc", "sim", str(spec), "--bag", str(bag), "--out",
               str(out), "--send-malformed", "--depth", str(frames), "--json"]  # fmt: skip
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=ROUND_TIMEOUT)
    except subprocess.TimeoutExpired:
        return False, Counter(k for k, _ in made), f"no answer in {ROUND_TIMEOUT} s"
    if result.returncode != 0:
        return False, Counter(k for k, _ in made), result.stderr.strip()[-400:]
    account = json.loads(result.stdout)
    got = [m.data for m in read_bag(out, types)]
    dropped = Counter({d["reason"]: d["count"] for d in account["dropped"] if d["where"] == "sub"})
    problems = []
    if got != expected:
        problems.append(f"{len(got)} messages out, {len(expected)} expected (or different)")
    if account["to_logic"] != {"sub": frames}:
        problems.append(f"to the logic: {account['to_logic']}")
    if sum(dropped.values()) != refused or len(account["dropped"]) != len(dropped):
        problems.append(f"dropped {account['dropped']}, {refused} refused")
    for reason in set(implied) | set(dropped):
        if not implied[reason] <= dropped[reason] <= implied[reason] + flipped:
            problems.append(f"{reason}: {dropped[reason]} counted, {implied[reason]} implied")
    return not problems, Counter(k for k, _ in made), "; ".join(problems)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=30.0, help="time for new rounds")
    parser.add_argument("--frames", type=int, default=24, help="frames in each round's bag")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    configs = list(itertools.product(MIDDLEWARES, WIDTHS, MESSAGES))
    rng.shuffle(configs)
    tried, handled = Counter(), Counter()
    rounds = passed = 0
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="rfc-fuzz-frames-") as scratch:
        for index, (middleware, width, message) in enumerate(itertools.cycle(configs)):
            if time.monotonic() - start > args.minutes * 60:
                break
            began = time.monotonic()
            ok, kinds, problem = run_round(
                Path(scratch) / str(index), middleware, width, message, args.frames, rng
            )
            rounds += 1
            passed += ok
            tried += kinds
            if ok:
                handled += kinds
            verdict = "ok" if ok else f"FAILED: {problem}"
            print(f"{middleware} {width:>2}-bit {message}: {sum(kinds.values())} frames, "
                  f"{time.monotonic() - began:.0f} s, {verdict}", flush=True)  # fmt: skip
    minutes = (time.monotonic() - start) / 60
    print(f"\n{rounds} rounds ({passed} passed) in {minutes:.1f} min, seed {args.seed}\n")
    print("| frames | tried | handled |\n|---|---:|---:|")
    for kind in KINDS:
        print(f"| {kind} | {tried[kind]:,} | {handled[kind]:,} |")
    print(f"| **all** | **{sum(tried.values()):,}** | **{sum(handled.values()):,}** |")
    if passed != rounds:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
