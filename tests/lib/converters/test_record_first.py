"""A publisher behind a record-first producer: the last stream straight through, no buffer.

The producer bench gives each message's earlier strings while the record is still unknown
(its ports hold noise), then the whole record with the first beat of ``data``, then the pixels,
and raises the message's valid once every beat has been taken. What the publisher sends must be
rosbags' serialization of the message, byte for byte; a producer that streams fewer or more
beats than it announced gets its frame padded with zeros or cut to the announced length, and
one more in ``error_count``.
"""

from __future__ import annotations

import random
from dataclasses import replace

import numpy as np
import pytest
from myhdl import StopSimulation, always, block, delay, instance

from rfc.lib.converters.buffer_sizes import buffers_of
from rfc.lib.converters.buffers import buffered_ports, buffered_publisher
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Direction, PortRole, Side, ports_of
from rfc.lib.converters.steps import Payload, Plan
from rfc.lib.converters.tables import tables
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.lib.converters.transactions import transactions
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
from rfc.messages.values import message_to_values
from rfc.toolchain import elaboration

IMAGE = "sensor_msgs/msg/Image"
LIMITS = Limits(string=24, sequence=512)
#: (height, width, encoding): odd sizes, an empty image, one row, one column.
SHAPES = [(3, 5, "rgb8"), (0, 0, "mono8"), (1, 17, "mono8"), (7, 1, "rgb8"), (4, 9, "mono8")]
TIMEOUT = 20_000


def images(middleware: Middleware, seed: int) -> list[object]:
    """rosbags Image messages of the `SHAPES`, random pixels and headers."""
    types = message_types(middleware)
    rng = np.random.default_rng(seed)
    made = []
    for index, (height, width, encoding) in enumerate(SHAPES):
        step = width * (3 if encoding == "rgb8" else 1)
        header = {"stamp": {"sec": index, "nanosec": 7 * index}, "frame_id": f"cam{index}" * index}
        if middleware is Middleware.ROS1:
            header["seq"] = index
        tree = {
            "header": header,
            "height": height,
            "width": width,
            "encoding": encoding,
            "is_bigendian": index % 2,
            "step": step,
            "data": rng.integers(0, 256, height * step, dtype=np.uint8),
        }
        made.append(types.build(IMAGE, tree))
    return made


def record_first(middleware: Middleware, width: int) -> Plan:
    """The Image publisher's plan behind a record-first producer."""
    layout = flatten(message_types(middleware), IMAGE)
    return replace(plan(layout, width, LIMITS), record_first=True)


def publish(
    chosen: Plan, messages: list, seed: int, extra: dict[tuple[int, str], int] | None = None
) -> tuple[list, int]:
    """Run the producer bench; return the frames (bytes, frame_length) and ``error_count``.

    `extra[(i, stream)]`: beats of that stream the producer sends beyond (or, negative, short
    of) what message `i` announces.
    """
    extra = extra or {}
    rng = random.Random(seed)
    ports = buffered_ports(chosen)
    signals = port_signals(ports)
    accelerator = ports_of(chosen, Side.PUBLISHER)
    record = [p.name for p in accelerator if p.group == "msg" and p.role in _DATA]
    last = chosen.steps[chosen.streamed_last]
    assert isinstance(last, Payload)
    earlier = [chosen.steps[at].stream for at in tables(chosen).streams if chosen.steps[at] != last]
    frames: list[tuple[bytes, int]] = []
    errors = []  # read before the simulation ends: MyHDL resets every signal then

    @block
    def bench():
        clk = signals["clk"]
        with elaboration():
            dut = top_block("dut", [p.name for p in ports], buffered_publisher, plan=chosen)
        unit = dut(**signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        def send(name, data):
            size = len(signals[f"{name}_tdata"]) // 8
            for start in range(0, len(data), size):
                while rng.random() < 0.3:
                    signals[f"{name}_tvalid"].next = 0
                    yield clk.posedge
                signals[f"{name}_tdata"].next = int.from_bytes(data[start : start + size], "little")
                signals[f"{name}_tvalid"].next = 1
                yield clk.posedge
                while not signals[f"{name}_tready"]:
                    yield clk.posedge
            signals[f"{name}_tvalid"].next = 0

        @instance
        def produce():
            signals["rst"].next = 1
            yield clk.posedge
            signals["rst"].next = 0
            for index, message in enumerate(messages):
                taken = transactions(chosen, message)
                for port in record:  # unknown while the earlier strings go
                    signals[port].next = rng.randrange(2 ** len(signals[port]))
                for name in (*earlier, last.stream):
                    if name == last.stream:
                        for port in record:
                            signals[port].next = taken.record[port]
                    data = b"".join(taken.streams.get(name, []))
                    beat = len(signals[f"{name}_tdata"]) // 8
                    size = max(0, len(data) + beat * extra.get((index, name), 0))
                    yield from send(name, (data + rng.randbytes(size))[:size])
                signals["msg_valid"].next = 1
                yield clk.posedge
                while not signals["msg_ready"]:
                    yield clk.posedge
                signals["msg_valid"].next = 0
            while len(frames) < len(messages):
                yield clk.posedge
            yield clk.posedge  # the last message's count shows after the edge that took it
            errors.append(int(signals["error_count"]))
            raise StopSimulation

        @instance
        def collect():
            frame = bytearray()
            width = len(signals["m_axis_tkeep"])
            for _ in range(TIMEOUT):
                signals["m_axis_tready"].next = rng.random() < 0.7
                yield clk.posedge
                if signals["m_axis_tvalid"] and signals["m_axis_tready"]:
                    keep = int(signals["m_axis_tkeep"])
                    chunk = int(signals["m_axis_tdata"]).to_bytes(width, "little")
                    frame += bytes(b for i, b in enumerate(chunk) if keep >> i & 1)
                    if signals["m_axis_tlast"]:
                        frames.append((bytes(frame), int(signals["frame_length"])))
                        frame.clear()
            raise AssertionError(f"publisher hung: {len(frames)} of {len(messages)} frames")

        return unit, clock, produce, collect

    with elaboration():
        simulation = bench()
        simulation.run_sim(quiet=1)
    return frames, errors[0]


_DATA = (PortRole.FIELD, PortRole.LENGTH, PortRole.COUNT)

CASES = [(m, w) for m in (Middleware.ROS1, Middleware.ROS2) for w in (8, 32, 64)]


@pytest.mark.parametrize(("middleware", "width"), CASES, ids=[f"{m.value}-{w}" for m, w in CASES])
def test_images_leave_byte_exact_with_only_the_short_strings_buffered(middleware, width):
    chosen = record_first(middleware, width)
    assert [b.path for b in buffers_of(chosen)] == ["header.frame_id", "encoding"]
    types = message_types(middleware)
    layout = flatten(types, IMAGE)
    messages = images(middleware, seed=width)
    values = [message_to_values(m, layout) for m in messages]
    frames, errors = publish(chosen, values, seed=width)
    expected = [types.serialize(m, IMAGE) for m in messages]
    assert frames == [(frame, len(frame)) for frame in expected]
    assert errors == 0


@pytest.mark.parametrize("middleware", [Middleware.ROS1, Middleware.ROS2])
def test_streams_short_or_long_of_their_length_are_padded_or_cut_and_counted(middleware):
    chosen = record_first(middleware, 32)  # beats of 4 bytes
    types = message_types(middleware)
    layout = flatten(types, IMAGE)
    messages = images(middleware, seed=5)
    values = [message_to_values(m, layout) for m in messages]
    # 3x5 rgb8: 45 pixel bytes, 2 beats short; the empty image as announced; 1x17: 8 bytes of
    # frame_id, a beat short; 7x1 rgb8: 12 bytes of frame_id, 2 beats more; 4x9: 3 beats more
    extra = {(0, "data"): -2, (2, "header_frame_id"): -1, (3, "header_frame_id"): 2,
             (4, "data"): 3}  # fmt: skip
    frames, errors = publish(chosen, values, seed=9, extra=extra)
    # what was announced, with the missing bytes zero: the beats sent are a prefix of it
    data, name = bytes(messages[0].data), messages[2].header.frame_id
    messages[0].data[:] = np.frombuffer(data[:-8] + bytes(8), np.uint8)
    messages[2].header.frame_id = name[:4] + "\0" * 4
    expected = [types.serialize(m, IMAGE) for m in messages]
    assert frames == [(frame, len(frame)) for frame in expected]
    assert errors == 4


def test_a_producer_that_is_not_record_first_keeps_every_stream_buffered():
    layout = flatten(message_types(Middleware.ROS2), IMAGE)
    chosen = plan(layout, 64, LIMITS)
    assert chosen.streamed_last is None
    assert [b.path for b in buffers_of(chosen)] == ["header.frame_id", "encoding", "data"]
    assert not any(p.name == "error_count" for p in buffered_ports(chosen))
    assert Direction.OUT in {p.direction for p in buffered_ports(replace(chosen, record_first=True))
                             if p.name == "error_count"}  # fmt: skip
