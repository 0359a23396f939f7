"""The prefix guard in MyHDL's simulator: only well-formed frames reach the subscriber, whole.

sensor_msgs/Image frames made by the reference codec (byte-exact with rosbags), damaged as in
the converter fuzz tests, go into the guard with the size a chunk header would declare for
them, random idle cycles and random back-pressure. What leaves it must be exactly the frames
the codec accepts within the maxima, byte for byte and in order, although the guard holds only
the bytes before ``data``; its counters must add up to the others.
"""

from __future__ import annotations

import random
from collections import Counter

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from myhdl import StopSimulation, always, block, delay, instance

from rfc.lib.converters.malformed import DROP_REASONS, counter_name
from rfc.lib.converters.plan import plan
from rfc.lib.converters.prefix_guard import DECLARED, prefix_guard, prefix_guard_ports
from rfc.lib.converters.prefix_plan import SLACK_BEATS, checking_plan
from rfc.lib.converters.toplevel import port_signals
from rfc.messages.codec import encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.selection import select
from rfc.toolchain import elaboration
from tests.hdl.converters.fuzz import candidates, verdict
from tests.hdl.converters.matrix import drawn_values

LIMITS = Limits(string=16, sequence=48, frame=1024)
#: The fields the image pipeline's subscriber hands on (encoding, step are parsed, not given).
INCLUDE = ["header", "height", "width", "data"]
#: Cycles a run may take before it counts as hung.
TIMEOUT = 100_000
#: Beats the buffer holds: the longest frame with empty ``data`` at LIMITS is 80 bytes.
PREFIX_BYTES = 80


def run_guard(checking, frames: list[tuple[bytes, int]], seed: int):
    """Send `frames` (bytes, declared size) through a guard; return what left it, and counters."""
    width = checking.width
    depth = -(-PREFIX_BYTES // width) + SLACK_BEATS
    signals = port_signals(prefix_guard_ports(width))
    rng = random.Random(seed)
    out: list[bytes] = []
    current = bytearray()
    done = [False]
    counts: dict[str, int] = {}

    @block
    def bench():
        clk = signals["clk"]
        dut = prefix_guard(checking, depth, **signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            signals["rst"].next = 1
            yield clk.posedge
            signals["rst"].next = 0
            for frame, declared in frames:
                signals[DECLARED].next = declared
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
            for _ in range(4 * depth + 400):  # room for the last verdict and frame
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


def image_layout(middleware: Middleware):
    return select(flatten(message_types(middleware), "sensor_msgs/msg/Image"), include=INCLUDE)


def image(index: int, pixels: int) -> dict[str, object]:
    """A mono8 image of `pixels` bytes (a frame with empty data is checked whole)."""
    return {
        "header.stamp.sec": index,
        "header.stamp.nanosec": 7,
        "header.frame_id": f"cam{index}",
        "height": 1,
        "width": pixels,
        "encoding": "mono8",
        "is_bigendian": 0,
        "step": pixels,
        "data": np.arange(pixels, dtype=np.uint8),
    }


CONFIGURATIONS = [(Middleware.ROS2, 32), (Middleware.ROS2, 64), (Middleware.ROS1, 64)]


@pytest.fixture
def messages(middleware):
    """Images the converters accept, drawn before hypothesis runs the test."""
    layout = image_layout(middleware)
    drawn = drawn_values(layout, f"prefix guard Image {middleware.value}", 8)
    converters = plan(layout, 8, LIMITS)
    return layout, [v for v in drawn if verdict(converters, encode(layout, v))[0] is False]


def test_the_checker_of_an_image_needs_only_the_bytes_before_data():
    checking = checking_plan(plan(image_layout(Middleware.ROS2), 8, LIMITS))
    assert checking is not None
    joint_state = flatten(message_types(Middleware.ROS2), "sensor_msgs/msg/JointState")
    assert checking_plan(plan(joint_state, 8, LIMITS)) is None  # string[] name: whole frames


@pytest.mark.parametrize(
    ("middleware", "width"), CONFIGURATIONS, ids=[f"{m.value}-{w}" for m, w in CONFIGURATIONS]
)
@settings(
    max_examples=4,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(seed=st.integers(0, 2**32 - 1))
def test_only_the_well_formed_frames_leave_the_prefix_guard_whole(messages, width, seed):
    layout, valid = messages
    converters = plan(layout, width, LIMITS)
    checking = checking_plan(converters)
    rng = random.Random(seed)
    pool = candidates(converters, valid, rng)
    frames = []
    while len(frames) < 8:
        frame = encode(layout, rng.choice(valid)) if rng.random() < 0.4 else next(pool)[1]
        if verdict(converters, frame)[0] is not None:
            frames.append(frame)
    sent, counts = run_guard(checking, [(f, len(f)) for f in frames], seed)
    assert sent == [f for f in frames if verdict(converters, f)[0] is False]
    assert sum(counts.values()) == len(frames) - len(sent)


@pytest.mark.parametrize("width", [32, 64])
def test_a_declared_size_other_than_the_frames_drops_it_before_data_moves(width):
    layout = image_layout(Middleware.ROS2)
    converters = plan(layout, width, LIMITS)
    good = [encode(layout, image(index, 3 + 5 * index)) for index in range(2)]
    assert all(verdict(converters, f)[0] is False for f in good)
    frames = [(good[0], len(good[0]) - 1), (good[1], len(good[1]) + 4), (good[0], len(good[0]))]
    sent, counts = run_guard(checking_plan(converters), frames, seed=width)
    assert sent == [good[0]]
    assert Counter({k: v for k, v in counts.items() if v}) == Counter(truncated=1, trailing=1)


@pytest.mark.parametrize("width", [32, 64])
def test_a_chunk_shorter_than_its_header_passes_as_documented_and_the_next_frame_is_clean(width):
    layout = image_layout(Middleware.ROS2)
    converters = plan(layout, width, LIMITS)
    whole, good = (encode(layout, image(index, 40)) for index in range(2))
    cut = whole[:-7]  # the DMA ended the chunk inside data, its header still says len(whole)
    sent, counts = run_guard(checking_plan(converters), [(cut, len(whole)), (good, len(good))],
                             seed=width)  # fmt: skip
    assert sent == [cut, good]  # the subscriber finds `cut` truncated at its end
    assert not any(counts.values())
