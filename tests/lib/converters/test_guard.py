"""The frame guard in MyHDL's simulator: exactly the well-formed frames go through, whole.

Frames made by the reference codec (byte-exact with rosbags), damaged as in the converter fuzz
tests, go into the guard with random idle cycles while its output is randomly back-pressured;
what leaves it must be exactly the frames the codec accepts within the maxima, byte for byte
and in order, and its counters must add up to the others. A frame longer than the guard's
buffer is dropped too.
"""

from __future__ import annotations

import random
from collections import Counter

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from myhdl import StopSimulation, always, block, delay, instance

from rfc.lib.converters.guard import frame_guard, guard_ports
from rfc.lib.converters.malformed import DROP_REASONS, counter_name
from rfc.lib.converters.plan import plan
from rfc.lib.converters.toplevel import port_signals
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.toolchain import elaboration
from tests.hdl.converters.fuzz import candidates, verdict
from tests.hdl.converters.matrix import drawn_values

LIMITS = Limits(string=16, sequence=6, frame=1024)
#: Cycles a run may take before it counts as hung.
TIMEOUT = 100_000


def run_guard(converters, depth: int, frames: list[bytes], seed: int):
    """Send `frames` through a guard; return the frames it sent on and its counters."""
    width = converters.width
    signals = port_signals(guard_ports(width))
    rng = random.Random(seed)
    out: list[bytes] = []
    current = bytearray()
    done = [False]
    counts: dict[str, int] = {}

    @block
    def bench():
        clk = signals["clk"]
        dut = frame_guard(converters, depth, **signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            signals["rst"].next = 1
            yield clk.posedge
            signals["rst"].next = 0
            for frame in frames:
                beats = [frame[i : i + width] for i in range(0, len(frame), width)] or [b""]
                for index, beat in enumerate(beats):
                    while rng.random() < 0.3:
                        signals["s_axis_tvalid"].next = 0
                        yield clk.posedge
                    signals["s_axis_tdata"].next = int.from_bytes(beat, "little")
                    signals["s_axis_tkeep"].next = (1 << len(beat)) - 1
                    signals["s_axis_tlast"].next = index == len(beats) - 1
                    signals["s_axis_tvalid"].next = 1
                    yield clk.posedge
                    while not signals["s_axis_tready"]:
                        yield clk.posedge
                signals["s_axis_tvalid"].next = 0
            for _ in range(4 * depth + 200):  # room for the last verdict and frame
                yield clk.posedge
            done[0] = True

        @instance
        def take():
            for _ in range(TIMEOUT):
                signals["m_axis_tready"].next = rng.random() < 0.7
                yield clk.posedge
                if signals["m_axis_tvalid"] and signals["m_axis_tready"]:
                    keep = int(signals["m_axis_tkeep"])
                    data = int(signals["m_axis_tdata"]).to_bytes(width, "little")
                    current.extend(b for i, b in enumerate(data) if keep >> i & 1)
                    if signals["m_axis_tlast"]:
                        out.append(bytes(current))
                        current.clear()
                if done[0]:  # MyHDL clears every signal when the simulation stops
                    counts.update({r.label: int(signals[counter_name(r)]) for r in DROP_REASONS})
                    raise StopSimulation
            raise AssertionError("the guard hung")

        return dut, clock, drive, take

    with elaboration():
        bench().run_sim(quiet=1)
    return out, counts


def depth_for(converters, frames: list[bytes]) -> int:
    """The buffer the system would give: the largest accepted frame, in beats, and then some."""
    return max(-(-len(f) // converters.width) for f in frames) + 2


CONFIGURATIONS = [(Middleware.ROS1, 8), (Middleware.ROS2, 32), (Middleware.ROS1, 64)]


@pytest.fixture
def messages(middleware):
    """JointState messages the converters accept, drawn before hypothesis runs the test."""
    layout = flatten(message_types(middleware), "sensor_msgs/msg/JointState")
    drawn = drawn_values(layout, f"guard JointState {middleware.value}", 6)
    converters = plan(layout, 8, LIMITS)
    return layout, [v for v in drawn if verdict(converters, encode(layout, v))[0] is False]


@pytest.mark.parametrize(
    ("middleware", "width"), CONFIGURATIONS, ids=[f"{m.value}-{w}" for m, w in CONFIGURATIONS]
)
@settings(
    max_examples=4,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(seed=st.integers(0, 2**32 - 1))
def test_only_the_well_formed_frames_leave_the_guard_whole(messages, width, seed):
    layout, valid = messages
    converters = plan(layout, width, LIMITS)
    rng = random.Random(seed)
    pool = candidates(converters, valid, rng)
    frames, kept = [], []
    while len(frames) < 8:
        frame = encode(layout, rng.choice(valid)) if rng.random() < 0.4 else next(pool)[1]
        rejected, _ = verdict(converters, frame)
        if rejected is None:
            continue
        frames.append(frame)
        if not rejected:
            kept.append(frame)
    depth = depth_for(converters, kept or frames)
    sent, counts = run_guard(converters, depth, frames, seed)
    assert sent == [f for f in frames if verdict(converters, f)[0] is False and len(f) <= depth
                    * width]  # fmt: skip
    assert sum(counts.values()) == len(frames) - len(sent)


def test_a_frame_longer_than_the_buffer_is_dropped_as_beyond_the_maximum():
    layout = flatten(message_types(Middleware.ROS2), "sensor_msgs/msg/JointState")
    converters = plan(layout, 8, LIMITS)
    valid = drawn_values(layout, "guard overflow", 2)
    good = encode(layout, valid[0])
    padded = good + bytes(40)  # trailing bytes: malformed, and longer than the buffer
    sent, counts = run_guard(converters, len(good) + 3, [padded, good], seed=5)
    assert sent == [good]
    assert Counter({k: v for k, v in counts.items() if v}) == Counter({"trailing": 1})
