"""Latencies of the generated blocks, measured in MyHDL's simulator for the build report.

The paper reports, for its quaternion system, the cycles its subscriber takes from the first
beat of a message to the fields (35), its accelerator from inputs to outputs (373), and its
publisher from the fields to the last beat (28). Each is measured here on one message of
default values with every ready held high: the best case, without backpressure. What stands in
front of a subscriber so that malformed frames end in the logic is measured too: a drop gate
(no cycle) and a frame guard, whose delay grows with the frame.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Generator, Mapping
from typing import Any

from myhdl import StopSimulation, block, delay, instance

from rfc.ir.infrastructure import Converter
from rfc.lib.converters.buffers import buffered_ports, buffered_publisher, buffers_of
from rfc.lib.converters.build import publisher_top, subscriber_top
from rfc.lib.converters.guard import frame_guard, guard_ports
from rfc.lib.converters.malformed import drop_gate, gate_ports
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Direction, Port, PortRole, Side, dma_ports, ports_of
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.messages.codec import Values, default_values, encode
from rfc.messages.limits import Limits
from rfc.passes.check_hardware import subscriber_guard
from rfc.toolchain.myhdl_state import elaboration, transient_signals

#: Cycles after which a measurement gives up (the block never answered).
_LIMIT = 20_000
_READY = (PortRole.READY, PortRole.TREADY)


def subscriber_latency(
    converter: Converter, limits: Limits, values: Values | None = None
) -> int | None:
    """Cycles from the first payload beat accepted to ``msg_valid`` (default `values`: zeros)."""
    chosen = plan(converter.layout, converter.bus_width, limits)
    ports = (*dma_ports(chosen, Side.SUBSCRIBER), *ports_of(chosen, Side.SUBSCRIBER))
    drive = _frame_into(_beats(converter, values), until="msg_valid")
    with elaboration():
        return _measure(subscriber_top(chosen), ports, drive)


def guard_latency(
    converter: Converter, limits: Limits, values: Values | None = None
) -> tuple[int, int] | None:
    """A frame through the subscriber's frame guard, or None when it has a drop gate instead.

    Args:
        converter: The subscriber.
        limits: The maxima the guard is built for.
        values: The message (default values unless given).

    Returns:
        The frame's beats, and the cycles from its first beat into the guard to its first beat
        out to the subscriber: the guard holds the frame until its checker has parsed it.
    """
    chosen = plan(converter.layout, converter.bus_width, limits)
    guard = subscriber_guard(converter, chosen, limits)
    if guard is None:
        return None
    ports = guard_ports(chosen.width)
    beats = _beats(converter, values)
    drive = _frame_into(beats, until="m_axis_tvalid")
    with elaboration():
        names = [p.name for p in ports]
        top = top_block("latency_dut", names, frame_guard, plan=chosen, depth=guard.words)
        cycles = _measure(top, ports, drive)
    return None if cycles is None else (len(beats), cycles)


def gate_latency() -> int | None:
    """Cycles a drop gate adds between a subscriber's ``msg_valid`` and its consumer's."""
    ports = gate_ports()

    def drive(s: Mapping[str, Any], cycle: Callable[[], Any]) -> Generator[Any, None, int | None]:
        s["s_valid"].next = 1
        for waited in range(_LIMIT):
            yield cycle()
            if s["m_valid"]:
                return waited
        return None

    with elaboration():
        return _measure(top_block("latency_dut", [p.name for p in ports], drop_gate), ports, drive)


def publisher_latency(converter: Converter, limits: Limits) -> int | None:
    """Cycles from ``msg_valid`` to the last beat accepted (with its buffers, as generated)."""
    chosen = plan(converter.layout, converter.bus_width, limits)
    ports = buffered_ports(chosen)

    def drive(s: Mapping[str, Any], cycle: Callable[[], Any]) -> Generator[Any, None, int | None]:
        s["msg_valid"].next = 1
        for waited in range(1, _LIMIT):
            yield cycle()
            if s["msg_ready"]:
                s["msg_valid"].next = 0
            if s["m_axis_tvalid"] and s["m_axis_tlast"]:
                return waited
        return None

    with elaboration():
        top = (
            top_block("latency_dut", [p.name for p in ports], buffered_publisher, plan=chosen)
            if buffers_of(chosen)
            else publisher_top(chosen)
        )
        return _measure(top, ports, drive)


def accelerator_latency(
    function: Any, ports: list[Port], inputs: list[str], outputs: list[str]
) -> int | None:
    """Cycles from every input's ``_valid`` to every output's ``_valid`` (all fields zero)."""

    def drive(s: Mapping[str, Any], cycle: Callable[[], Any]) -> Generator[Any, None, int | None]:
        for name in inputs:
            s[f"{name}_valid"].next = 1
        seen: set[str] = set()
        for waited in range(1, _LIMIT):
            yield cycle()
            for name in inputs:
                if s[f"{name}_ready"]:
                    s[f"{name}_valid"].next = 0
            seen |= {name for name in outputs if s[f"{name}_valid"]}
            if len(seen) == len(outputs):
                return waited
        return None

    with elaboration():
        return _measure(top_block("latency_dut", [p.name for p in ports], function), ports, drive)


# A build measures every converter; MyHDL would keep each bench's signals for the process's life.
@transient_signals()
def _measure(top: Any, ports: tuple[Port, ...] | list[Port], drive: Any) -> int | None:
    signals = port_signals(ports)
    result: list[int | None] = [None]

    @block
    def bench() -> Any:
        dut = top(**signals)
        clk, rst = signals["clk"], signals["rst"]

        @instance
        def clock() -> Generator[Any, None, None]:
            while True:
                yield delay(5)
                clk.next = not clk

        @instance
        def run() -> Generator[Any, None, None]:
            for port in ports:
                if port.direction is Direction.IN and port.role in _READY:
                    signals[port.name].next = 1
            rst.next = 1
            for _ in range(3):
                yield clk.posedge
            rst.next = 0
            result[0] = yield from drive(signals, lambda: clk.posedge)
            raise StopSimulation

        return dut, clock, run

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        instance_ = bench()
        instance_.run_sim(quiet=True)
        instance_.quit_sim()
    return result[0]


def _beats(converter: Converter, values: Values | None) -> list[bytes]:
    """The message's frame (default values unless given) cut into beats of the bus."""
    frame = encode(converter.layout, default_values(converter.layout) if values is None else values)
    lanes = converter.bus_width // 8
    return [frame[i : i + lanes] for i in range(0, len(frame), lanes)]


def _frame_into(beats: list[bytes], until: str) -> Callable[..., Generator[Any, None, int | None]]:
    """A driver feeding `beats` to ``s_axis``: cycles from the first beat taken to `until`."""

    def drive(s: Mapping[str, Any], cycle: Callable[[], Any]) -> Generator[Any, None, int | None]:
        now, first = 0, None
        for index, beat in enumerate(beats):
            s["s_axis_tdata"].next = int.from_bytes(beat, "little")  # little-endian lanes
            s["s_axis_tkeep"].next = (1 << len(beat)) - 1
            s["s_axis_tlast"].next = index == len(beats) - 1
            s["s_axis_tvalid"].next = 1
            accepted = False
            while not accepted and now < _LIMIT:
                yield cycle()
                now += 1
                accepted = bool(s["s_axis_tready"])
            first = now if first is None else first
        s["s_axis_tvalid"].next = 0
        while not s[until] and now < _LIMIT:
            yield cycle()
            now += 1
        return None if now >= _LIMIT or first is None else now - first + 1

    return drive
