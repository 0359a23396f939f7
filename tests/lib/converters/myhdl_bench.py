"""Run converters in MyHDL's own simulator: frames and transactions in, what came out back.

Every handshake the bench drives or takes is randomly idle or back-pressured (seeded), as the
cocotb benches do on GHDL.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field

from myhdl import StopSimulation, always, block, delay, instance, join

from rfc.lib.converters.build import publisher_top, subscriber_top
from rfc.lib.converters.ports import Direction, PortRole, Side, dma_ports, ports_of
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.toplevel import port_signals
from rfc.lib.converters.transactions import Transactions
from rfc.toolchain import elaboration

#: Cycles a bench may run before it gives up (a hang is a failure, not a wait).
TIMEOUT = 200_000


@dataclass
class Parsed:
    """What a subscriber presented for one frame."""

    message: Transactions = field(default_factory=Transactions)
    error: bool = False
    reason: int = 0


def _groups(plan: Plan, side: Side) -> tuple[list, list, list]:
    ports = ports_of(plan, side)
    streams = sorted({p.group for p in ports if p.role is PortRole.TDATA})
    channels = sorted({p.group for p in ports if p.role is PortRole.VALID and p.group != "msg"})
    return list(ports), streams, channels


def simulate_subscriber(plan: Plan, frames: list[bytes], seed: int = 1) -> list[Parsed]:
    """Send `frames` to the plan's subscriber; return what it presented, frame by frame."""
    rng = random.Random(seed)
    signals = port_signals((*dma_ports(plan, Side.SUBSCRIBER), *ports_of(plan, Side.SUBSCRIBER)))
    ports, streams, channels = _groups(plan, Side.SUBSCRIBER)
    record_ports = [p.name for p in ports if p.group == "msg" and p.role in _DATA]
    width = plan.width
    results: list[Parsed] = []
    current = Parsed()
    pending: dict[str, bytearray] = {name: bytearray() for name in streams}

    @block
    def bench():
        clk = signals["clk"]
        dut = subscriber_top(plan)(**signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            signals["rst"].next = 1
            yield clk.posedge
            signals["rst"].next = 0
            for frame in frames:
                beats = [frame[i : i + width] for i in range(0, len(frame), width)]
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

        @instance
        def consume():
            nonlocal current
            for _ in range(TIMEOUT):
                for name in ("msg", *channels):
                    signals[f"{name}_ready"].next = rng.random() < 0.7
                for name in streams:
                    signals[f"{name}_tready"].next = rng.random() < 0.7
                yield clk.posedge
                for name in streams:
                    if signals[f"{name}_tvalid"] and signals[f"{name}_tready"]:
                        keep = int(signals[f"{name}_tkeep"])
                        data = int(signals[f"{name}_tdata"])
                        size = len(signals[f"{name}_tkeep"])
                        chunk = data.to_bytes(size, "little")
                        pending[name] += bytes(b for i, b in enumerate(chunk) if keep >> i & 1)
                        if signals[f"{name}_tlast"]:
                            current.message.streams.setdefault(name, []).append(
                                bytes(pending[name])
                            )
                            pending[name].clear()
                for name in channels:
                    if signals[f"{name}_valid"] and signals[f"{name}_ready"]:
                        element = {
                            p.name: int(signals[p.name])
                            for p in ports
                            if p.group == name and p.role in _DATA
                        }
                        current.message.elements.setdefault(name, []).append(element)
                if signals["msg_valid"] and signals["msg_ready"]:
                    current.message.record = {n: int(signals[n]) for n in record_ports}
                    current.error = bool(signals["msg_error"])
                    current.reason = int(signals["error_reason"])
                    results.append(current)
                    current = Parsed()
                    if len(results) == len(frames):
                        raise StopSimulation
            raise AssertionError(f"subscriber hung: {len(results)} of {len(frames)} frames")

        return dut, clock, drive, consume

    with elaboration():
        simulation = bench()
    simulation.run_sim(quiet=1)
    return results


_DATA = (PortRole.FIELD, PortRole.LENGTH, PortRole.COUNT)


def simulate_publisher(
    plan: Plan, messages: list[Transactions], seed: int = 1
) -> list[tuple[bytes, int]]:
    """Give `messages` to the plan's publisher; return each frame it sent and its length port."""
    rng = random.Random(seed)
    signals = port_signals((*dma_ports(plan, Side.PUBLISHER), *ports_of(plan, Side.PUBLISHER)))
    ports, streams, channels = _groups(plan, Side.PUBLISHER)
    inputs = {p.name for p in ports if p.direction is Direction.IN}
    results: list[tuple[bytes, int]] = []

    @block
    def bench():
        clk = signals["clk"]
        dut = publisher_top(plan)(**signals)

        @always(delay(5))
        def clock():
            clk.next = not clk

        def stream_source(name, message_index):
            size = len(signals[f"{name}_tdata"]) // 8
            for data in messages[message_index].streams.get(name, []):
                for start in range(0, len(data), size):
                    while rng.random() < 0.3:
                        signals[f"{name}_tvalid"].next = 0
                        yield clk.posedge
                    chunk = data[start : start + size]
                    signals[f"{name}_tdata"].next = int.from_bytes(chunk, "little")
                    signals[f"{name}_tvalid"].next = 1
                    yield clk.posedge
                    while not signals[f"{name}_tready"]:
                        yield clk.posedge
                signals[f"{name}_tvalid"].next = 0

        def channel_source(name, message_index):
            for element in messages[message_index].elements.get(name, []):
                while rng.random() < 0.3:
                    signals[f"{name}_valid"].next = 0
                    yield clk.posedge
                for port, value in element.items():
                    signals[port].next = value
                signals[f"{name}_valid"].next = 1
                yield clk.posedge
                while not signals[f"{name}_ready"]:
                    yield clk.posedge
                signals[f"{name}_valid"].next = 0

        @instance
        def drive():
            signals["rst"].next = 1
            yield clk.posedge
            signals["rst"].next = 0
            for index, message in enumerate(messages):
                for port, value in message.record.items():
                    if port in inputs:
                        signals[port].next = value
                signals["msg_valid"].next = 1
                sources = [stream_source(n, index) for n in streams]
                sources += [channel_source(n, index) for n in channels]
                yield join(*sources, _until(clk, signals["msg_ready"]))
                signals["msg_valid"].next = 0

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
                        results.append((bytes(frame), int(signals["frame_length"])))
                        frame.clear()
                        if len(results) == len(messages):
                            raise StopSimulation
            raise AssertionError(f"publisher hung: {len(results)} of {len(messages)} frames")

        return dut, clock, drive, collect

    with elaboration():
        simulation = bench()
    simulation.run_sim(quiet=1)
    return results


def _until(clk, flag):
    yield clk.posedge
    while not flag:
        yield clk.posedge


def visible(message: Transactions) -> Transactions:
    """What a bench can observe of a message: empty string/sequence instances send no beats."""
    streams = {}
    for name, items in message.streams.items():
        if any(items):
            streams[name] = [item for item in items if item]
    elements = {name: items for name, items in message.elements.items() if items}
    return Transactions(dict(message.record), streams, elements)
