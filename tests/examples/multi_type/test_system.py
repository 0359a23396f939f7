"""examples/multi_type in the generated logic: strings and sequences pass through byte-exact.

Each publisher takes its message's strings and sequences only after the record, while the
subscriber in front hands them over as it parses: the publishers' buffers hold them. Images,
scans and twists of random sizes go through the whole logic in GHDL; what comes out must be the
very bytes rosbags serialized. Messages beyond the example's maxima are counted as dropped for
that reason before they reach the logic.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
SPEC = ROOT / "examples/multi_type/MultiType.yaml"
TOPICS = {
    "/camera/image": ("sensor_msgs/msg/Image", "/camera/image_out"),
    "/scan": ("sensor_msgs/msg/LaserScan", "/scan_out"),
    "/cmd_vel": ("geometry_msgs/msg/TwistStamped", "/cmd_vel_out"),
}


def header(rng: np.random.Generator) -> dict:
    name = "".join(rng.choice(list("abcdefgh_/"), size=rng.integers(0, 20)))
    return {"stamp": {"sec": int(rng.integers(2**31)), "nanosec": 7}, "frame_id": name}


def image(rng: np.random.Generator) -> dict:
    height, width = (int(v) for v in rng.integers(1, 9, size=2))
    encoding, channels = ("rgb8", 3) if rng.random() < 0.5 else ("mono8", 1)
    return {
        "header": header(rng),
        "height": height,
        "width": width,
        "encoding": encoding,
        "is_bigendian": 0,
        "step": width * channels,
        "data": rng.integers(0, 256, height * width * channels, dtype=np.uint8),
    }


def scan(rng: np.random.Generator) -> dict:
    beams = int(rng.integers(0, 40))
    values = [float(v) for v in rng.normal(size=7).astype(np.float32)]
    names = ("angle_min", "angle_max", "angle_increment", "time_increment", "scan_time")
    return {
        "header": header(rng),
        **dict(zip((*names, "range_min", "range_max"), values, strict=True)),
        "ranges": rng.normal(size=beams).astype(np.float32),
        "intensities": rng.normal(size=int(rng.integers(0, 3)) * beams).astype(np.float32),
    }


def twist(rng: np.random.Generator) -> dict:
    x, y, z, a, b, c = (float(v) for v in rng.normal(size=6))
    return {
        "header": header(rng),
        "twist": {"linear": {"x": x, "y": y, "z": z}, "angular": {"x": a, "y": b, "z": c}},
    }


def test_every_message_comes_out_of_the_logic_as_rosbags_serialized_it(tmp_path):
    rng = np.random.default_rng(7)
    types = message_types("ros2")
    makers = {"/camera/image": image, "/scan": scan, "/cmd_vel": twist}
    messages = []
    for index in range(36):
        topic = list(makers)[index % 3]
        kind = TOPICS[topic][0]
        data = types.serialize(types.build(kind, makers[topic](rng)), kind)
        messages.append((topic, 1_000_000 * (index + 1), data))
    # beyond the maxima (images of 230,400 bytes, scans of 2,048 beams, 64-byte strings)
    too_long = [
        ("/camera/image", image(rng) | {"height": 1, "width": 76_801, "step": 230_403,
                                        "encoding": "rgb8", "data": np.ones(230_403, np.uint8)}),
        ("/scan", scan(rng) | {"ranges": np.zeros(2049, np.float32)}),
        ("/cmd_vel", twist(rng) | {"header": {"stamp": {"sec": 1, "nanosec": 2},
                                              "frame_id": "x" * 65}}),
    ]  # fmt: skip
    refused = [
        (
            topic,
            1_000_000 * (40 + i),
            types.serialize(types.build(TOPICS[topic][0], v), TOPICS[topic][0]),
        )
        for i, (topic, v) in enumerate(too_long)
    ]
    bag = tmp_path / "in.mcap"
    write_bag(bag, types, {t: k for t, (k, _) in TOPICS.items()}, messages + refused)

    out = tmp_path / "out.mcap"
    result = run_rfc("sim", SPEC, "--bag", bag, "--out", out, "--json", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert account["received"] == dict.fromkeys(TOPICS, 13)
    assert account["published"] == {o: 12 for _, o in TOPICS.values()}
    assert account["dropped"] == [
        {"where": where, "reason": "maximum", "count": 1}
        for where in ("Image_sub", "Scan_sub", "Twist_sub")
    ]
    outputs = [(m.topic, m.timestamp_ns, m.data) for m in read_bag(out, types)]
    renamed = {t: o for t, (_, o) in TOPICS.items()}
    expected = [(renamed[t], stamp, data) for t, stamp, data in messages]
    assert sorted(outputs) == sorted(expected)
