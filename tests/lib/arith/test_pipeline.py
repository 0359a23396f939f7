"""The pipeline plumbing: the result queue keeps order and loses nothing under backpressure."""

from __future__ import annotations

import pytest
from myhdl import ResetSignal, Signal, always_comb, block, intbv

from rfc.lib.arith.pipeline import result_queue
from rfc.toolchain import convert_myhdl
from tests.support.cosim import run_handshake
from tests.support.myhdl_stream import simulate_stream

ORDER = ("clk", "rst", "in_valid", "in_ready", "data", "out_valid", "out_ready", "result")


@block
def queue_with_handshake(clk, rst, in_valid, in_ready, data, out_valid, out_ready, result, depth):
    """The queue fed by a producer that offers `data` and pushes while the queue has room."""
    push, room = Signal(bool(0)), Signal(bool(0))
    queue = result_queue(clk, rst, push, data, room, out_valid, out_ready, result, depth)

    @always_comb
    def producer():
        in_ready.next = room
        push.next = in_valid and room

    return queue, producer


def ports() -> dict[str, Signal]:
    signals = {name: Signal(bool(0)) for name in ORDER}
    signals["rst"] = ResetSignal(0, active=1, isasync=False)
    signals["data"], signals["result"] = Signal(intbv(0)[40:]), Signal(intbv(0)[40:])
    return signals


VALUES = [(i * 0x9E3779B1) % (1 << 40) for i in range(200)]


@pytest.mark.parametrize("depth", [2, 3, 4, 7])
@pytest.mark.parametrize("backpressure", [0.0, 0.5, 0.9])
def test_results_leave_in_order_none_lost_or_repeated(depth, backpressure):
    signals = ports()
    run = simulate_stream(
        queue_with_handshake,
        [*(signals[n] for n in ORDER), depth],
        signals,
        {"data": VALUES},
        ["result"],
        idle=0.3,
        backpressure=backpressure,
        seed=depth,
    )
    assert run.outputs["result"] == VALUES


def test_takes_a_result_every_cycle_while_the_consumer_keeps_up():
    signals = ports()
    run = simulate_stream(
        queue_with_handshake,
        [*(signals[n] for n in ORDER), 4],
        signals,
        {"data": VALUES[:20]},
        ["result"],
        idle=0.0,
        backpressure=0.0,
    )
    assert run.outputs["result"] == VALUES[:20]
    assert {run.accepted[i + 1] - run.accepted[i] for i in range(19)} == {1}


def test_converted_vhdl_keeps_order_under_backpressure(tmp_path):
    signals = ports()
    dut = queue_with_handshake(*(signals[n] for n in ORDER), 4)
    files = convert_myhdl(dut, "queue", tmp_path)
    run = run_handshake(files, "queue", {"data": VALUES}, ["result"], tmp_path)
    assert run.outputs["result"] == VALUES
