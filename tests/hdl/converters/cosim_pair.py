"""cocotb bench for a converter pair (`pair.py`) in GHDL, driven by a JSON scenario.

The scenario (path in ``RFC_SCENARIO``, written by `scenario.py`) lists frames for the
subscriber with what it must present for each, and messages for the publisher with the frames
it must send. AXI-Stream traffic goes through cocotbext-axi's sources and sinks, the record
handshakes through the small drivers below; every handshake the bench controls is randomly
idle or back-pressured.
"""

from __future__ import annotations

import json
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge, with_timeout
from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamSink, AxiStreamSource

#: How often a source idles and a sink holds tready low.
PAUSE = 0.3


async def _pause_randomly(clk, rng: random.Random, drivers: list) -> None:
    """Pause each cocotbext-axi driver on a random 30 % of cycles (one coroutine for all)."""
    while True:
        for driver in drivers:
            driver.pause = rng.random() < PAUSE
        await RisingEdge(clk)


def _signal(dut, name):
    return getattr(dut, name)


class Bucket:
    """What the subscriber presented for one frame."""

    def __init__(self) -> None:
        self.streams: dict[str, list[str]] = {}
        self.elements: dict[str, list[dict[str, int]]] = {}


async def _subscriber(dut, scenario, rng, results):
    side = scenario["subscriber"]
    clk = dut.clk
    source = AxiStreamSource(AxiStreamBus.from_prefix(dut, "sub_s_axis"), clk, dut.rst)
    sinks = {
        name: AxiStreamSink(AxiStreamBus.from_prefix(dut, f"sub_{name}"), clk, dut.rst)
        for name in side["streams"]
    }
    cocotb.start_soon(_pause_randomly(clk, rng, [source, *sinks.values()]))
    for frame in side["frames"]:
        await source.send(AxiStreamFrame(bytes.fromhex(frame)))
    record_ports = side["record"]
    channels = side["channels"]
    bucket = Bucket()
    while len(results) < len(side["frames"]):
        for name in ("msg", *channels):
            _signal(dut, f"sub_{name}_ready").value = int(rng.random() >= PAUSE)
        await RisingEdge(clk)
        for name, ports in channels.items():
            valid = _signal(dut, f"sub_{name}_valid").value
            ready = _signal(dut, f"sub_{name}_ready").value
            if valid == 1 and ready == 1:
                element = {p: int(_signal(dut, f"sub_{p}").value) for p in ports}
                bucket.elements.setdefault(name, []).append(element)
        if dut.sub_msg_valid.value == 1 and dut.sub_msg_ready.value == 1:
            for name, sink in sinks.items():
                while not sink.empty():
                    data = (await sink.recv()).tdata
                    bucket.streams.setdefault(name, []).append(bytes(data).hex())
            record = {p: int(_signal(dut, f"sub_{p}").value) for p in record_ports}
            results.append((record, bucket, int(dut.sub_msg_error.value)))
            bucket = Bucket()


async def _drive_record(dut, clk, rng, name, values):
    while rng.random() < PAUSE:
        await RisingEdge(clk)
    for port, value in values.items():
        _signal(dut, f"pub_{port}").value = value
    _signal(dut, f"pub_{name}_valid").value = 1
    await RisingEdge(clk)
    while _signal(dut, f"pub_{name}_ready").value != 1:
        await RisingEdge(clk)
    _signal(dut, f"pub_{name}_valid").value = 0


async def _publisher(dut, scenario, rng, frames, lengths):
    side = scenario["publisher"]
    clk = dut.clk
    sink = AxiStreamSink(AxiStreamBus.from_prefix(dut, "pub_m_axis"), clk, dut.rst)
    sources = {
        name: AxiStreamSource(AxiStreamBus.from_prefix(dut, f"pub_{name}"), clk, dut.rst)
        for name in side["streams"]
    }
    cocotb.start_soon(_pause_randomly(clk, rng, [sink, *sources.values()]))
    cocotb.start_soon(_watch_lengths(dut, lengths))
    for message in side["messages"]:
        for name, items in message["streams"].items():
            for item in items:
                if item:
                    await sources[name].send(AxiStreamFrame(bytes.fromhex(item)))
        tasks = [
            cocotb.start_soon(_drive_elements(dut, clk, rng, name, elements))
            for name, elements in message["elements"].items()
        ]
        await _drive_record(dut, clk, rng, "msg", message["record"])
        for task in tasks:
            await task
    while len(frames) < len(side["messages"]):
        frames.append(bytes((await sink.recv()).tdata).hex())


async def _drive_elements(dut, clk, rng, name, elements):
    for element in elements:
        await _drive_record(dut, clk, rng, name, element)


async def _watch_lengths(dut, lengths):
    first = True
    while True:
        await RisingEdge(dut.clk)
        if dut.pub_m_axis_tvalid.value == 1 and dut.pub_m_axis_tready.value == 1:
            if first:
                lengths.append(int(dut.pub_frame_length.value))
            first = dut.pub_m_axis_tlast.value == 1


@cocotb.test()
async def converters_match_rosbags(dut):
    """Subscriber presents rosbags' values; publisher sends rosbags' bytes."""
    with open(os.environ["RFC_SCENARIO"]) as file:
        scenario = json.load(file)
    rng = random.Random(scenario["seed"])
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.rst.value = 1
    dut.pub_msg_valid.value = 0
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    parsed, frames, lengths = [], [], []
    sub = cocotb.start_soon(_subscriber(dut, scenario, rng, parsed))
    pub = cocotb.start_soon(_publisher(dut, scenario, rng, frames, lengths))
    await with_timeout(sub, scenario["timeout_us"], "us")
    await with_timeout(pub, scenario["timeout_us"], "us")
    _check_subscriber(scenario["subscriber"], parsed)
    await RisingEdge(dut.clk)  # the counter counts the last message on its handshake's edge
    errors = sum(1 for item in scenario["subscriber"]["expected"] if item["error"])
    assert int(dut.sub_error_count.value) == errors, (
        f"error_count {int(dut.sub_error_count.value)}, expected {errors}"
    )
    _check_publisher(scenario["publisher"], frames, lengths)


def _check_subscriber(side, parsed):
    for index, (expected, (record, bucket, error)) in enumerate(
        zip(side["expected"], parsed, strict=True)
    ):
        where = f"{side['label']} frame {index}"
        assert error == expected["error"], (
            f"{where}: msg_error {error}, expected {expected['error']}"
        )
        if expected["error"]:
            continue
        assert record == expected["record"], f"{where}: record {record} != {expected['record']}"
        assert bucket.streams == expected["streams"], (
            f"{where}: streams {bucket.streams} != {expected['streams']}"
        )
        assert bucket.elements == expected["elements"], (
            f"{where}: elements {bucket.elements} != {expected['elements']}"
        )


def _check_publisher(side, frames, lengths):
    for index, (frame, length, expected) in enumerate(
        zip(frames, lengths, side["frames"], strict=True)
    ):
        where = f"{side['label']} message {index}"
        assert frame == expected, f"{where}: sent {frame}, rosbags serializes {expected}"
        assert length == len(expected) // 2, (
            f"{where}: frame_length {length}, sent {len(frame) // 2}"
        )
