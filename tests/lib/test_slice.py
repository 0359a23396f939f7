"""The register slice between blocks, in MyHDL's simulator.

Under random valid and ready every message comes out once, in order, fields intact; it takes a
message every cycle when the consumer always takes one; it holds a message while the consumer
stalls, so the producer can finish the next one meanwhile.
"""

from __future__ import annotations

import random

import pytest
from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance, intbv

from rfc.lib.slice import slice_body

#: A message of a bool and two vectors, as the top level hands the slice a message's fields.
FIELDS = (("flag", 1, True), ("x", 12, False), ("y", 5, False))


def message(n: int) -> dict[str, int]:
    return {"flag": n % 3 == 0, "x": (n * 7919) & 0xFFF, "y": (n * 31) & 0x1F}


def run(seed: int, p_valid: float, p_ready: float, count: int = 300) -> dict:
    """Offer `count` messages to a slice; return what came out and when."""
    clk, rst = Signal(bool(0)), ResetSignal(0, active=1, isasync=False)
    ports = {"clk": clk, "rst": rst}
    ports |= {f"{side}_{hs}": Signal(bool(0)) for side in "sm" for hs in ("valid", "ready")}
    for name, bits, single in FIELDS:
        for side in "sm":
            ports[f"{side}_{name}"] = Signal(bool(0)) if single else Signal(intbv(0)[bits:])
    seen = {"out": [], "cycles": 0, "taken": [], "given": []}

    @block
    def bench():
        dut = slice_body(FIELDS, **ports)

        @always(delay(5))
        def tick():
            clk.next = not clk

        @instance
        def drive():
            rng, sent = random.Random(seed), 0
            while len(seen["out"]) < count:
                yield clk.negedge
                offer = sent < count and rng.random() < p_valid
                ports["s_valid"].next = offer
                for name, value in message(sent).items():
                    ports[f"s_{name}"].next = value
                ports["m_ready"].next = rng.random() < p_ready
                yield clk.posedge
                if ports["s_valid"] and ports["s_ready"]:
                    seen["taken"].append(seen["cycles"])
                    sent += 1
                if ports["m_valid"] and ports["m_ready"]:
                    out = {name: int(ports[f"m_{name}"]) for name, _, _ in FIELDS}
                    seen["out"].append(out)
                    seen["given"].append(seen["cycles"])
                seen["cycles"] += 1
            raise StopSimulation

        return dut, tick, drive

    bench().run_sim(quiet=1)
    return seen


@pytest.mark.parametrize("seed", range(4))
def test_every_message_comes_out_once_in_order_under_random_handshakes(seed):
    seen = run(seed, p_valid=0.7, p_ready=0.5)
    assert seen["out"] == [{k: int(v) for k, v in message(n).items()} for n in range(300)]


def test_one_message_per_cycle_when_the_consumer_always_takes_one():
    seen = run(0, p_valid=1.0, p_ready=1.0, count=200)
    assert seen["cycles"] <= 200 + 1  # one cycle through the register, then one a cycle


def test_it_holds_the_next_message_while_the_consumer_works_on_one_and_no_more_than_two():
    # the consumer takes a message one cycle in ten, the producer always has the next
    seen = run(1, p_valid=1.0, p_ready=0.1, count=40)
    taken, given = seen["taken"], seen["given"]
    assert len(given) == 40
    # message n + 1 was taken from the producer before the consumer took message n
    assert any(taken[n + 1] < given[n] for n in range(39))
    # never more than two inside: the output register and the skid register
    inside = [sum(t <= c for t in taken) - sum(g < c for g in given) for c in range(len(taken))]
    assert max(inside) == 2
