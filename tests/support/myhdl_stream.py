"""Stream items through a valid/ready MyHDL block in MyHDL's simulator, like the cocotb bench.

The same protocol and latency definition as `tests.support.handshake_bench`, so that MyHDL
simulation and GHDL co-simulation of one block are held to the same expectations.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from myhdl import Signal, StopSimulation, block, delay, instance

from rfc.toolchain import elaboration
from tests.support.cosim import HandshakeRun


def simulate_stream(
    block_function: Callable[..., Any],
    arguments: Sequence[Any],
    ports: Mapping[str, Signal],
    inputs: Mapping[str, Sequence[int]],
    outputs: Sequence[str],
    *,
    idle: float = 0.3,
    backpressure: float = 0.3,
    seed: int = 1,
    timeout_cycles: int = 10_000,
) -> HandshakeRun:
    """Drive ``block_function(*arguments)`` with `inputs`; return its outputs and latencies.

    The block is built inside the bench (MyHDL wants sub-blocks built in a block's own body).

    `ports` holds clk, rst, in_valid, in_ready, out_valid, out_ready and the data ports by name;
    values are the signals' own integers (signed where the signal is).
    """
    rng = random.Random(seed)
    count = len(next(iter(inputs.values())))
    seen: dict[str, list[int]] = {name: [] for name in outputs}
    latencies: list[int] = []
    accepted: list[int] = []
    clk, rst = ports["clk"], ports["rst"]

    @block
    def bench():
        @instance
        def run():
            rst.next = 1
            for _ in range(2):
                yield delay(5)
                clk.next = 1
                yield delay(5)
                clk.next = 0
            rst.next = 0
            sent = edge = last_progress = 0
            taken_at: list[int] = []
            valid_at: list[int] = []
            offering = False
            while len(seen[outputs[0]]) < count:
                if not offering and sent < count and rng.random() >= idle:
                    for name, values in inputs.items():
                        ports[name].next = values[sent]
                    offering = True
                ports["in_valid"].next = offering
                out_ready = rng.random() >= backpressure
                ports["out_ready"].next = out_ready
                yield delay(5)
                # Sample what the design sees at the coming edge, then make the edge.
                handshake = offering and bool(ports["in_ready"].val)
                out_valid = bool(ports["out_valid"].val)
                results = {name: int(ports[name].val) for name in outputs}
                clk.next = 1
                edge += 1
                if handshake:
                    taken_at.append(edge)
                    sent += 1
                    offering = False
                    last_progress = edge
                if out_valid:
                    if len(valid_at) == len(seen[outputs[0]]):
                        valid_at.append(edge)
                    if out_ready:
                        for name, value in results.items():
                            seen[name].append(value)
                        last_progress = edge
                if edge - last_progress >= timeout_cycles:
                    raise AssertionError(
                        f"no progress for {timeout_cycles} cycles: the block hangs"
                    )
                yield delay(5)
                clk.next = 0
            latencies.extend(v - t - 1 for t, v in zip(taken_at, valid_at, strict=True))
            accepted.extend(taken_at)
            raise StopSimulation

        dut = block_function(*arguments)
        return dut, run

    with elaboration():  # MyHDL's own elaboration reads every caller's source context
        bench().run_sim(quiet=True)
    return HandshakeRun(seen, latencies, accepted)
