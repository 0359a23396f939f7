"""The FIFO of the publishers' buffers, in MyHDL's simulator and (converted) in GHDL.

Under random valid and ready on both sides every word comes out once, in order; it holds
`depth` + 1 words and refuses more; a word keeps one per cycle flowing when both sides are
always ready.
"""

from __future__ import annotations

import random

import pytest
from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance, intbv

from rfc.lib.converters.fifo import fifo


def run(depth: int, seed: int, p_valid: float, p_ready: float, words: int = 400) -> dict:
    """Push `words` words through a FIFO of `depth`; return what came out and the occupancy."""
    clk, rst = Signal(bool(0)), ResetSignal(0, active=1, isasync=False)
    in_data, out_data = Signal(intbv(0)[16:]), Signal(intbv(0)[16:])
    in_valid, in_ready, out_valid, out_ready = (Signal(bool(0)) for _ in range(4))
    seen = {"out": [], "peak": 0, "cycles": 0}

    @block
    def bench():
        dut = fifo(clk, rst, in_data, in_valid, in_ready, out_data, out_valid, out_ready, depth)

        @always(delay(5))
        def tick():
            clk.next = not clk

        @instance
        def drive():
            rng, sent, held = random.Random(seed), 0, 0
            while len(seen["out"]) < words:
                yield clk.negedge
                in_valid.next = sent < words and rng.random() < p_valid
                in_data.next = (sent * 7919) & 0xFFFF
                out_ready.next = rng.random() < p_ready
                yield clk.posedge
                if in_valid and in_ready:
                    sent, held = sent + 1, held + 1
                if out_valid and out_ready:
                    seen["out"].append(int(out_data))
                    held -= 1
                seen["peak"] = max(seen["peak"], held)
                seen["cycles"] += 1
            raise StopSimulation

        return dut, tick, drive

    bench().run_sim(quiet=1)
    return seen


@pytest.mark.parametrize("depth", [2, 3, 8])
@pytest.mark.parametrize("seed", range(3))
def test_every_word_comes_out_once_in_order_under_random_handshakes(depth, seed):
    seen = run(depth, seed, p_valid=0.7, p_ready=0.5)
    assert seen["out"] == [(n * 7919) & 0xFFFF for n in range(400)]


@pytest.mark.parametrize("depth", [2, 5])
def test_it_holds_depth_plus_one_words_and_no_more(depth):
    seen = run(depth, seed=1, p_valid=1.0, p_ready=0.05, words=60)
    assert seen["peak"] == depth + 1


def test_one_word_per_cycle_when_both_sides_are_always_ready():
    seen = run(4, seed=0, p_valid=1.0, p_ready=1.0, words=200)
    assert seen["cycles"] <= 200 + 3  # two cycles to fall through, then one word a cycle
