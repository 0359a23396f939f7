"""A MyHDL bench for image stages: images in as a subscriber gives them, images out.

Each stage gets sensor_msgs/Image interface objects built from rfc's message signature; a
chain of stages is joined member by member as the top level joins them. The feeder plays the
subscriber (stamp, then frame_id streamed, then height and width, then the data stream, then
the message's ``valid``); the collector plays the publisher. `Traffic` sets how often the
feeder idles between beats and how often the collector takes a beat or a message: the stage
tests use random gaps and back-pressure, `tools/bench_image.py` a full-rate feeder and
collector to count cycles. `run_chain` returns each output image with its stamp, frame_id,
step and encoding, and the cycles from the first input data beat to the last output beat.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from myhdl import ResetSignal, Signal, Simulation, StopSimulation, delay, instance

from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side, accelerator_signature
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.interface import interface_object
from rfc.lib.passthrough import typed_pass_through
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import message_types
from rfc.messages.selection import select

IMAGE = "sensor_msgs/msg/Image"
FRAME = ["header", "height", "width", "data"]
#: What the pipeline publishes of its last stage's image (all but the byte order).
WITH_ENCODING = [*FRAME, "encoding", "step", "is_bigendian"]


@dataclass(frozen=True)
class Picture:
    """One image message: the pixels (height by width, or by 3 for rgb8) and its header."""

    pixels: np.ndarray
    sec: int
    nanosec: int
    frame_id: str


@dataclass(frozen=True)
class Result:
    """One output message as the collector saw it."""

    height: int
    width: int
    data: bytes
    sec: int
    nanosec: int
    frame_id: str
    step: int | None
    encoding: str | None


@dataclass(frozen=True)
class Traffic:
    """How the bench's ends behave, as probabilities per cycle.

    Attributes:
        idle: The feeder holds a beat back.
        take_beat: The collector takes a beat offered.
        take_message: The collector takes a message offered.
    """

    idle: float = 0.3
    take_beat: float = 0.7
    take_message: float = 0.5


#: The ends at full rate: a beat every cycle, everything taken at once.
FULL_RATE = Traffic(0.0, 1.0, 1.0)


@dataclass(frozen=True)
class Run:
    """What came out of a bench run.

    Attributes:
        results: The output messages, in order.
        first_beat: The cycle the first input data beat was taken.
        last_beat: The cycle the last output data beat was taken.
    """

    results: list[Result]
    first_beat: int
    last_beat: int

    @property
    def cycles(self) -> int:
        """Cycles from the first input data beat to the last output data beat, both counted."""
        return self.last_beat - self.first_beat + 1


def image_port(side: Side, include: list[str], width: int):
    """An interface object of sensor_msgs/Image with the given fields, for bus `width`."""
    layout = select(flatten(message_types("ros2"), IMAGE), include=include)
    limits = Limits(string=64, fields={"data": 1920 * 1080 * 3})
    signature = accelerator_signature(plan(layout, width, limits), side, "p")
    port, _ = interface_object(signature, port_signals(signature), "port p")
    return port


def run_stage(stage, pictures: list[Picture], output: list[str], width: int = 64, seed: int = 0):
    """Feed `pictures` through `stage` (a MyHDL block function); the output messages."""
    return run_chain([stage], pictures, output, width, Traffic(), seed).results


def run_chain(
    stages: list,
    pictures: list[Picture],
    output: list[str],
    width: int = 64,
    traffic: Traffic = FULL_RATE,
    seed: int = 0,
    limit: int = 200_000,
) -> Run:
    """Feed `pictures` through `stages` one after the other; `output`: the last one's fields.

    Raises:
        AssertionError: Not every image came out within `limit` cycles.
    """
    rng = np.random.default_rng(seed)
    source = image_port(Side.SUBSCRIBER, FRAME, width)
    clk, rst = Signal(bool(0)), ResetSignal(1, active=1, isasync=False)
    blocks, here = [], source
    for index, stage in enumerate(stages):
        last = index == len(stages) - 1
        target = image_port(Side.PUBLISHER, output if last else FRAME, width)
        blocks.append(stage(clk, rst, here, target))
        if not last:  # the next stage's input, joined as the top level joins them
            here = image_port(Side.SUBSCRIBER, FRAME, width)
            blocks.append(typed_pass_through(clk, rst, target, here))
    results: list[Result] = []
    stamps = {"first": -1, "last": -1, "now": 0}

    def chance(p: float) -> bool:
        return p >= 1 or bool(rng.random() < p)

    def beats(raw: bytes, size: int) -> list[int]:
        return [int.from_bytes(raw[i : i + size], "little") for i in range(0, len(raw), size)]

    @instance
    def clock():
        while True:
            yield delay(5)
            clk.next = not clk

    def send(stream, raw: bytes):
        size = len(stream.data) // 8
        stream.length.next = len(raw)
        yield clk.posedge
        for beat in beats(raw, size):
            while traffic.idle and chance(traffic.idle):
                stream.valid.next = 0
                yield clk.posedge
            stream.data.next = beat
            stream.valid.next = 1
            yield clk.posedge
            while not stream.ready:
                yield clk.posedge
            if stream is source.data and stamps["first"] < 0:
                stamps["first"] = stamps["now"]
            stream.valid.next = 0

    @instance
    def count():
        while True:
            yield clk.posedge
            stamps["now"] += 1

    @instance
    def feed():
        yield clk.posedge
        yield clk.posedge
        rst.next = 0
        for picture in pictures:
            source.header.stamp.sec.next = picture.sec
            source.header.stamp.nanosec.next = picture.nanosec
            yield from send(source.header.frame_id, picture.frame_id.encode())
            source.height.next, source.width.next = picture.pixels.shape[:2]
            yield from send(source.data, picture.pixels.tobytes())
            source.valid.next = 1
            yield clk.posedge
            while not source.ready:
                yield clk.posedge
            source.valid.next = 0

    @instance
    def collect():
        streams = output_streams(target)
        received: dict[str, bytearray] = {name: bytearray() for name in streams}
        for _ in range(limit):
            for stream in streams.values():
                stream.ready.next = chance(traffic.take_beat)
            target.ready.next = chance(traffic.take_message)
            yield clk.posedge
            for name, stream in streams.items():
                if stream.valid and stream.ready:
                    size = len(stream.data) // 8
                    received[name] += int(stream.data).to_bytes(size, "little")
                    if name == "data":
                        stamps["last"] = stamps["now"]
            if target.valid and target.ready:
                results.append(snapshot(target, received))
                received = {name: bytearray() for name in streams}
                if len(results) == len(pictures):
                    raise StopSimulation
        raise AssertionError(f"{len(results)} of {len(pictures)} images out after {limit} cycles")

    Simulation(*blocks, clock, count, feed, collect).run(quiet=True)
    return Run(results, stamps["first"], stamps["last"])


def output_streams(target) -> dict:
    """The output's streams by name (plain Python: MyHDL does not analyse it)."""
    streams = {"data": target.data, "frame_id": target.header.frame_id}
    if hasattr(target, "encoding"):
        streams["encoding"] = target.encoding
    return streams


def snapshot(target, received: dict[str, bytearray]) -> Result:
    """The output message now taken, with the stream bytes received for it."""

    def text(name: str, stream) -> str:
        return bytes(received[name][: int(stream.length)]).decode()

    encoding = getattr(target, "encoding", None)
    step = getattr(target, "step", None)
    return Result(
        int(target.height),
        int(target.width),
        bytes(received["data"][: int(target.data.length)]),
        int(target.header.stamp.sec),
        int(target.header.stamp.nanosec),
        text("frame_id", target.header.frame_id),
        None if step is None else int(step),
        None if encoding is None else text("encoding", encoding),
    )


def random_pictures(rng: np.random.Generator, sizes: list[tuple[int, int]], channels: int):
    """Random images of the given sizes, each with its own stamp and frame_id."""
    shape = (channels,) if channels > 1 else ()
    return [
        Picture(
            rng.integers(0, 256, size=(h, w, *shape), dtype=np.uint8),
            index,
            7 * index,
            "camera_frame"[: index % 12],
        )
        for index, (h, w) in enumerate(sizes)
    ]
