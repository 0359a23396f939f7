"""The subscriber under malformed input, in GHDL: flag, count, drop, resynchronize — never hang.

Thousands of malformed frames (early tlast, trailing bytes, flipped bits, garbage, lengths over
the configured maximum, wrong CDR encapsulation) are interleaved with valid ones; every valid
one must still be presented exactly, every malformed one flagged with ``msg_error``, and
``error_count`` must count them all (the bench checks both).
"""

from __future__ import annotations

import random
from collections import Counter

import pytest

from rfc.lib.converters.plan import plan
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.toolchain import run_cocotb
from tests.hdl.converters.fuzz import candidates, verdict
from tests.hdl.converters.matrix import drawn_values
from tests.hdl.converters.pair import build_pair
from tests.hdl.converters.scenario import subscriber_scenario, write_scenario

#: One valid frame comes between every few malformed ones.
VALID_EVERY = 4


def fuzz_items(converters, values, rng, malformed):
    """Frames with their values (None when malformed), and how many of each kind were made."""
    items, made = [], Counter()
    pool = candidates(converters, values, rng)
    while sum(made.values()) < malformed:
        if rng.randrange(VALID_EVERY) == 0:
            chosen = rng.choice(values)
            items.append((encode(converters.layout, chosen), chosen))
            continue
        kind, frame = next(pool)
        rejected, decoded = verdict(converters, frame)
        if rejected is not None:
            made[kind] += rejected
            items.append((frame, None if rejected else decoded))
    return items, made


@pytest.mark.slow
@pytest.mark.parametrize(
    ("type_name", "width", "malformed"),
    [("sensor_msgs/msg/JointState", 32, 2000), ("tf2_msgs/msg/TFMessage", 64, 500)],
)
def test_malformed_frames_are_flagged_and_valid_ones_still_decoded(
    type_name, width, malformed, tmp_path
):
    layout = flatten(message_types(Middleware.ROS2), type_name)
    converters = plan(layout, width, Limits(string=16, sequence=6, frame=2048))
    drawn = drawn_values(layout, f"fuzz {type_name}", 30)
    values = [v for v in drawn if verdict(converters, encode(layout, v))[0] is False]
    items, made = fuzz_items(converters, values, random.Random(width), malformed)
    assert set(made) == {"truncated", "trailing", "flipped", "garbage", "too long", "header"}
    content = subscriber_scenario(converters, items, label=f"fuzz {type_name}", seed=width)
    files = build_pair(converters, tmp_path / "hdl")
    run_cocotb(
        files,
        "pair",
        "tests.hdl.converters.cosim_pair",
        tmp_path / "sim",
        env={"RFC_SCENARIO": str(write_scenario(tmp_path / "scenario.json", content))},
        seed=width,
    )
