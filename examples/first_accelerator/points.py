"""Points for the first-accelerator tutorial: make a bag of them, or compare a mirrored bag.

python points.py make points.mcap [N]
python points.py compare points.mcap mirrored.mcap
"""

import sys

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag

POINT = "geometry_msgs/msg/Point"


def make(path, count=100):
    """Write `count` random points to /points."""
    types = message_types("ros2")
    rng = np.random.default_rng(1)
    values = rng.normal(size=(count, 3))
    points = [types.build(POINT, {"x": x, "y": y, "z": z}) for x, y, z in values.tolist()]
    messages = [("/points", 1000 * i, types.serialize(p, POINT)) for i, p in enumerate(points, 1)]
    write_bag(path, types, {"/points": POINT}, messages)


def compare(points_bag, mirrored_bag):
    """Exit 1 unless every point came out with x negated, y and z kept."""
    types = message_types("ros2")
    sent = [types.deserialize(m.data, POINT) for m in read_bag(points_bag, types, ["/points"])]
    got = [types.deserialize(m.data, POINT) for m in read_bag(mirrored_bag, types, ["/mirrored"])]
    good = sum((q.x, q.y, q.z) == (-p.x, p.y, p.z) for p, q in zip(sent, got, strict=False))
    print(f"{good} of {len(sent)} points mirrored exactly")
    sys.exit(0 if good == len(sent) == len(got) else 1)


if __name__ == "__main__":
    if sys.argv[1] == "make":
        make(sys.argv[2], *map(int, sys.argv[3:]))
    else:
        compare(sys.argv[2], sys.argv[3])
