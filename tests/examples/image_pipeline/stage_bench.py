"""A MyHDL bench for one image stage: images in as a subscriber gives them, images out.

The stage gets sensor_msgs/Image interface objects built from rfc's message signature. The
feeder plays the subscriber (stamp, then frame_id streamed, then height and width, then the
data stream, then the message's ``valid``, with idle cycles between beats); the collector
plays the publisher (random back-pressure on every stream and on the message). `run_stage`
returns each output image as NumPy sees it, with its stamp, frame_id, step and encoding.
"""

from __future__ import annotations

import importlib
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from myhdl import ResetSignal, Signal, Simulation, StopSimulation, delay, instance

from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side, accelerator_signature
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.interface import interface_object
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import message_types
from rfc.messages.selection import select

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "image_pipeline"
IMAGE = "sensor_msgs/msg/Image"
FRAME = ["header", "height", "width", "data"]


def example_module(name: str):
    """A module of the example (its stages import their helpers by plain name)."""
    if str(EXAMPLE) not in sys.path:
        sys.path.insert(0, str(EXAMPLE))
    return importlib.import_module(name)


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


def image_port(side: Side, include: list[str], width: int):
    """An interface object of sensor_msgs/Image with the given fields, for bus `width`."""
    layout = select(flatten(message_types("ros2"), IMAGE), include=include)
    limits = Limits(string=64, fields={"data": 20000})
    signature = accelerator_signature(plan(layout, width, limits), side, "p")
    port, _ = interface_object(signature, port_signals(signature), "port p")
    return port


def run_stage(stage, pictures: list[Picture], output: list[str], width: int = 64, seed: int = 0):
    """Feed `pictures` through `stage` (a MyHDL block function); the output messages."""
    rng = np.random.default_rng(seed)
    source = image_port(Side.SUBSCRIBER, FRAME, width)
    target = image_port(Side.PUBLISHER, output, width)
    clk, rst = Signal(bool(0)), ResetSignal(1, active=1, isasync=False)
    results: list[Result] = []
    dut = stage(clk, rst, source, target)

    def chance(p: float) -> bool:
        return bool(rng.random() < p)

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
            while chance(0.3):
                stream.valid.next = 0
                yield clk.posedge
            stream.data.next = beat
            stream.valid.next = 1
            yield clk.posedge
            while not stream.ready:
                yield clk.posedge
            stream.valid.next = 0

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
        for _ in range(200_000):
            for stream in streams.values():
                stream.ready.next = chance(0.7)
            target.ready.next = chance(0.5)
            yield clk.posedge
            for name, stream in streams.items():
                if stream.valid and stream.ready:
                    size = len(stream.data) // 8
                    received[name] += int(stream.data).to_bytes(size, "little")
            if target.valid and target.ready:
                results.append(snapshot(target, received))
                received = {name: bytearray() for name in streams}
                if len(results) == len(pictures):
                    raise StopSimulation
        raise AssertionError(f"{len(results)} of {len(pictures)} images out after 200,000 cycles")

    Simulation(dut, clock, feed, collect).run(quiet=True)
    return results


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
