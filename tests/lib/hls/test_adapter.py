"""The ap_ctrl wrapper against a behavioural Vitis HLS core (ap_ctrl_hs, ap_none in, ap_vld out).

The core computes ``a + b`` and ``a - b`` after a random number of cycles (UG1399's block-level
protocol: ap_start is sampled in the idle state, ap_done/ap_ready last one cycle, after which
the core is idle again); the wrapper must
start it once per pair of input messages, take each input exactly once, and offer each result
until the consumer (random backpressure) takes it.
"""

from __future__ import annotations

import random

import pytest
from myhdl import StopSimulation, block, delay, instance

from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.lib.hls.adapter import AdapterShape, StreamPort, hls_adapter
from rfc.lower.system.components import adapter_ports
from rfc.toolchain import elaboration

SHAPE = AdapterShape(
    inputs=("a", "b"),
    outputs=(
        ("sum", (("sum_v", "core_sum", 16, 16),)),
        ("diff", (("diff_v", "core_diff", 16, 16),)),
    ),
)
MASK = 0xFFFF


def run(pairs: list[tuple[int, int]], seed: int) -> tuple[list[int], list[int], int]:
    rng = random.Random(seed)
    ports = adapter_ports(SHAPE)
    s = port_signals(ports)
    sums: list[int] = []
    diffs: list[int] = []
    starts = [0]

    @block
    def bench():
        dut = top_block("adapter", [p.name for p in ports], hls_adapter, shape=SHAPE)(**s)

        @instance
        def clock():
            while True:
                yield delay(5)
                s["clk"].next = not s["clk"]

        @instance
        def core():  # ap_ctrl_hs: ap_start sampled when idle; done and ready for one cycle,
            # after which the core is back to idle (it samples ap_start from the next edge)
            while True:
                yield s["clk"].posedge
                if not s["ap_start"]:
                    continue
                starts[0] += 1
                s["ap_idle"].next = 0
                a, b = inputs[0]
                for _ in range(rng.randrange(0, 6)):
                    yield s["clk"].posedge
                s["core_sum"].next = (a + b) & MASK
                s["core_diff"].next = (a - b) & MASK
                s["core_sum_ap_vld"].next = s["core_diff_ap_vld"].next = 1
                s["ap_done"].next = s["ap_ready"].next = 1
                yield s["clk"].posedge
                s["ap_done"].next = s["ap_ready"].next = 0
                s["core_sum_ap_vld"].next = s["core_diff_ap_vld"].next = 0
                s["ap_idle"].next = 1

        inputs = [(0, 0)]

        @instance
        def producer():  # both input messages valid together, each held until taken
            s["rst"].next = 1
            for _ in range(3):
                yield s["clk"].posedge
            s["rst"].next = 0
            for a, b in pairs:
                inputs[0] = (a, b)
                s["a_valid"].next = s["b_valid"].next = 1
                taken = set()
                while len(taken) < 2:
                    yield s["clk"].posedge
                    taken |= {n for n in "ab" if s[f"{n}_ready"]}
                    for n in taken:
                        s[f"{n}_valid"].next = 0
                for _ in range(rng.randrange(0, 3)):
                    yield s["clk"].posedge

        @instance
        def consumer():
            while len(sums) < len(pairs) or len(diffs) < len(pairs):
                s["sum_ready"].next = rng.random() < 0.6
                s["diff_ready"].next = rng.random() < 0.6
                yield s["clk"].posedge
                if s["sum_valid"] and s["sum_ready"]:
                    sums.append(int(s["sum_v"]))
                if s["diff_valid"] and s["diff_ready"]:
                    diffs.append(int(s["diff_v"]))
            raise StopSimulation

        return dut, clock, core, producer, consumer

    with elaboration():
        simulation = bench()
        simulation.run_sim(duration=200_000, quiet=True)
        simulation.quit_sim()
    return sums, diffs, starts[0]


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_one_call_per_message_and_every_result_delivered_once(seed):
    rng = random.Random(seed)
    pairs = [(rng.randrange(MASK), rng.randrange(MASK)) for _ in range(40)]
    sums, diffs, starts = run(pairs, seed)
    assert sums == [(a + b) & MASK for a, b in pairs]
    assert diffs == [(a - b) & MASK for a, b in pairs]
    assert starts == len(pairs)


STREAMS = AdapterShape(
    inputs=("a",),
    outputs=(("sum", (("sum_length", "core_sum_length", 6, 32),)),),
    sources=(StreamPort("a_s", "core_a_s", 8, 32),),
    sinks=(StreamPort("sum_s", "core_sum_s", 8, 32),),
)


def run_streams(messages: list[bytes], seed: int) -> tuple[list[bytes], int]:
    """Each message's bytes on a sub-stream, its valid raised only after the last beat is taken
    (as a subscriber does); a core that writes each byte plus one and then sets the length."""
    rng = random.Random(seed)
    ports = adapter_ports(STREAMS)
    s = port_signals(ports)
    received: list[bytes] = []
    starts = [0]

    @block
    def bench():
        dut = top_block("adapter", [p.name for p in ports], hls_adapter, shape=STREAMS)(**s)

        @instance
        def clock():
            while True:
                yield delay(5)
                s["clk"].next = not s["clk"]

        @instance
        def core():  # ap_fifo in and out; done, ready and the length's ap_vld in the last state
            while True:
                yield s["clk"].posedge
                if not s["ap_start"]:
                    continue
                starts[0] += 1
                count = len(messages[starts[0] - 1])  # what the struct's length would say
                for _ in range(count):
                    s["core_a_s_read"].next = 0
                    s["core_sum_s_write"].next = 0
                    yield s["clk"].negedge
                    while not (s["core_a_s_empty_n"] and s["core_sum_s_full_n"]):
                        yield s["clk"].negedge
                    s["core_sum_s_din"].next = (int(s["core_a_s_dout"]) + 1) & 0xFF
                    s["core_a_s_read"].next = s["core_sum_s_write"].next = 1
                    yield s["clk"].posedge
                s["core_a_s_read"].next = s["core_sum_s_write"].next = 0
                s["core_sum_length"].next = count
                s["core_sum_length_ap_vld"].next = 1
                s["ap_done"].next = s["ap_ready"].next = 1
                yield s["clk"].posedge
                s["ap_done"].next = s["ap_ready"].next = 0
                s["core_sum_length_ap_vld"].next = 0

        @instance
        def producer():
            s["rst"].next = 1
            for _ in range(3):
                yield s["clk"].posedge
            s["rst"].next = 0
            for data in messages:
                for start in range(0, len(data), 4):
                    chunk = data[start : start + 4]
                    s["a_s_tdata"].next = int.from_bytes(chunk.ljust(4, b"\0"), "little")
                    s["a_s_tkeep"].next = (1 << len(chunk)) - 1
                    s["a_s_tvalid"].next = 1
                    yield s["clk"].posedge
                    while not s["a_s_tready"]:
                        yield s["clk"].posedge
                    s["a_s_tvalid"].next = 0
                for _ in range(rng.randrange(0, 8)):
                    yield s["clk"].posedge
                s["a_valid"].next = 1
                yield s["clk"].posedge
                while not s["a_ready"]:
                    yield s["clk"].posedge
                s["a_valid"].next = 0

        beats: list[bytes] = []

        @instance
        def fifo():  # the FIFO in front of the publisher: takes beats before the record
            while True:
                s["sum_s_tready"].next = rng.random() < 0.6
                yield s["clk"].posedge
                if s["sum_s_tvalid"] and s["sum_s_tready"]:
                    beats.append(int(s["sum_s_tdata"]).to_bytes(4, "little"))

        @instance
        def consumer():  # the publisher: the record, then its length's bytes from the FIFO
            while len(received) < len(messages):
                s["sum_ready"].next = rng.random() < 0.5
                yield s["clk"].posedge
                if s["sum_valid"] and s["sum_ready"]:
                    length = int(s["sum_length"])
                    while len(beats) * 4 < length:
                        yield s["clk"].posedge
                    used = -(-length // 4)
                    received.append(b"".join(beats[:used])[:length])
                    del beats[:used]
            raise StopSimulation

        return dut, clock, core, producer, fifo, consumer

    with elaboration():
        simulation = bench()
        simulation.run_sim(duration=400_000, quiet=True)
        simulation.quit_sim()
    return received, starts[0]


@pytest.mark.parametrize("seed", [1, 2])
def test_a_stream_starts_the_core_before_its_message_is_valid(seed):
    rng = random.Random(seed)
    messages = [bytes(rng.randrange(256) for _ in range(n)) for n in (9, 0, 1, 4, 13, 0, 7)]
    received, starts = run_streams(messages, seed)
    assert received == [bytes((b + 1) & 0xFF for b in m) for m in messages]
    assert starts == len(messages)
