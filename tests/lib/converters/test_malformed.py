"""Damaged frames in MyHDL's simulator: the subscriber rejects exactly them, and says why.

Frames made by the reference codec (byte-exact with rosbags) from drawn messages, then
truncated, extended, lengthened beyond a maximum, given a wrong CDR encapsulation, bit-flipped
or replaced by garbage (`tests.hdl.converters.fuzz`), are mixed with valid ones. The codec's
verdict decides which frames are malformed; the subscriber must flag exactly those, give the
reason the damage implies where it implies one, and still present every valid frame exactly.
"""

from __future__ import annotations

import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rfc.lib.converters.malformed import Reason
from rfc.lib.converters.plan import plan
from rfc.lib.converters.transactions import transactions
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from tests.hdl.converters.fuzz import candidates, verdict
from tests.hdl.converters.matrix import drawn_values
from tests.lib.converters.myhdl_bench import simulate_subscriber, visible

#: Small maxima, so that lengthened strings and sequences are quick to make and to send.
LIMITS = Limits(string=16, sequence=6, frame=1024)
#: The reason each kind of damage implies when the codec refuses the frame (others: any).
IMPLIED = {
    "truncated": Reason.TRUNCATED,
    "trailing": Reason.TRAILING,
    "too long": Reason.MAXIMUM,
    "header": Reason.ENCODING,
}
CONFIGURATIONS = [(m, w) for m in (Middleware.ROS1, Middleware.ROS2) for w in (8, 32, 64)]


@pytest.fixture
def messages(middleware):
    """JointState messages the converters accept, drawn before hypothesis runs the test.

    Read-only, so sharing it between the generated inputs is safe.
    """
    layout = flatten(message_types(middleware), "sensor_msgs/msg/JointState")
    drawn = drawn_values(layout, f"malformed JointState {middleware.value}", 8)
    converters = plan(layout, 8, LIMITS)
    return layout, [v for v in drawn if verdict(converters, encode(layout, v))[0] is False]


@pytest.mark.parametrize(
    ("middleware", "width"), CONFIGURATIONS, ids=[f"{m.value}-{w}" for m, w in CONFIGURATIONS]
)
@settings(
    max_examples=5,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(seed=st.integers(0, 2**32 - 1))
def test_the_subscriber_rejects_exactly_the_damaged_frames_and_says_why(messages, width, seed):
    layout, valid = messages
    converters = plan(layout, width, LIMITS)
    rng = random.Random(seed)
    pool = candidates(converters, valid, rng)
    frames, expected = [], []
    while len(frames) < 10:
        if rng.random() < 0.3:
            values = rng.choice(valid)
            frames.append(encode(layout, values))
            expected.append(("valid", values))
            continue
        kind, frame = next(pool)
        rejected, values = verdict(converters, frame)
        if rejected is not None:
            frames.append(frame)
            expected.append((kind, None if rejected else values))

    parsed = simulate_subscriber(converters, frames, seed=seed)

    for index, ((kind, values), result) in enumerate(zip(expected, parsed, strict=True)):
        where = f"frame {index} ({kind})"
        assert result.error is (values is None), where
        if values is not None:
            assert result.reason == Reason.NONE, where
            assert result.message == visible(transactions(converters, values)), where
        elif kind in IMPLIED:
            assert Reason(result.reason) is IMPLIED[kind], where
        else:
            assert result.reason in [int(r) for r in Reason if r is not Reason.NONE], where
