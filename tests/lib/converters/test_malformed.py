"""Damaged frames in MyHDL's simulator: the subscriber rejects exactly them, and says why.

Frames made by the reference codec (byte-exact with rosbags) from drawn messages, then
truncated, extended, lengthened beyond a maximum, given a wrong CDR encapsulation, bit-flipped
or replaced by garbage (`tests.hdl.converters.fuzz`), are mixed with valid ones. The codec's
verdict decides which frames are malformed; the subscriber must flag exactly those, give the
reason the damage implies where it implies one, and still present every valid frame exactly.
"""

from __future__ import annotations

import random
from collections import Counter

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from myhdl import ResetSignal, Signal, StopSimulation, block, delay, instance, intbv

from rfc.lib.converters.malformed import DROP_REASONS, Reason, counter_name, drop_gate, gate_ports
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


def through_gate(reasons, consumer_ready, seed):
    """Records through a drop gate: which passed, the counters, the cycles each was offered.

    `reasons` holds each record's reason (``Reason.NONE`` for a valid one). The subscriber
    offers a record after a random pause and holds it until the gate's `s_ready`;
    `consumer_ready(rng, valid)` is the consumer's ready on a cycle, `valid` whether a valid
    record is offered.
    """
    rng = random.Random(seed)
    ports = {p.name: Signal(intbv(0)[p.bits :]) if p.bits > 1 else Signal(bool(0))
             for p in gate_ports()}  # fmt: skip
    ports["rst"] = ResetSignal(0, active=1, isasync=False)
    clk = ports["clk"]
    passed, offered, counts = [], [], {}

    @block
    def bench():
        gate = drop_gate(**ports)

        @instance
        def clock():
            while True:
                yield delay(5)
                clk.next = not clk

        @instance
        def subscriber_and_consumer():
            for index, reason in enumerate(reasons):
                for _ in range(rng.randrange(3)):
                    yield clk.posedge
                ports["s_valid"].next = True
                ports["s_error"].next = reason is not Reason.NONE
                ports["s_reason"].next = int(reason)
                cycles, taken = 0, False
                while not taken:
                    ports["m_ready"].next = consumer_ready(rng, reason is Reason.NONE)
                    yield clk.negedge  # the gate's outputs have settled
                    taken = bool(ports["s_ready"])
                    if ports["m_valid"] and ports["m_ready"]:
                        passed.append(index)
                    yield clk.posedge
                    cycles += 1
                offered.append(cycles)
                ports["s_valid"].next = False
                ports["m_ready"].next = False
            yield clk.negedge
            counts.update({r: int(ports[counter_name(r)].val) for r in DROP_REASONS})
            raise StopSimulation  # MyHDL clears every signal after the run

        return gate, clock, subscriber_and_consumer

    bench().run_sim(quiet=True)
    return passed, counts, offered


def drawn_reasons(seed, count=60):
    rng = random.Random(seed)
    return [rng.choice([Reason.NONE, Reason.NONE, *DROP_REASONS]) for _ in range(count)]


@pytest.mark.parametrize(
    "waits_for_valid", [False, True], ids=["ready-any-time", "ready-waits-for-valid"]
)
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_drop_gate_passes_valid_records_and_counts_the_rejected_ones(seed, waits_for_valid):
    # a consumer may raise ready only for a valid record (AXI allows it): the gate must still
    # take the rejected ones, or the subscriber would hang
    def ready(rng, valid):
        return (valid or not waits_for_valid) and rng.random() < 0.5

    reasons = drawn_reasons(seed)
    passed, counts, _ = through_gate(reasons, ready, seed)
    assert passed == [i for i, r in enumerate(reasons) if r is Reason.NONE]
    rejected = Counter(r for r in reasons if r is not Reason.NONE)
    assert counts == {r: rejected[r] for r in DROP_REASONS}


def test_a_rejected_record_is_taken_at_once_or_from_the_gate_s_own_register_a_cycle_later():
    # s_ready follows the consumer's ready or a flip-flop of the gate, never the subscriber's
    # error flag in the same cycle: a rejected record the consumer is not ready for waits one
    reasons = [Reason.TRUNCATED, Reason.NONE, Reason.TRAILING, Reason.ENCODING]
    _, _, offered = through_gate(reasons, lambda rng, valid: True, seed=0)
    assert offered == [1, 1, 1, 1]
    _, _, offered = through_gate(reasons, lambda rng, valid: valid, seed=0)
    assert offered == [2, 1, 2, 2]
