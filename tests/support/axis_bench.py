"""cocotb helpers for benches: clock/reset, and the vector-valid streams the manager uses.

The manager shares `tdata`/`tkeep`/`tlast` among its converters and keeps one `tvalid`/`tready`
bit per converter, which cocotbext-axi's single-stream drivers cannot map; `VectorSink`
collects such streams, one packet list per lane of the vector.
"""

from __future__ import annotations

import json
import os
import random
from pathlib import Path
from typing import Any

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge


def bench_case() -> dict[str, Any]:
    """The case a pytest test wrote for this bench (path in RFC_BENCH_CASE)."""
    return json.loads(Path(os.environ["RFC_BENCH_CASE"]).read_text())


async def start(dut: Any, clock: str = "clk", reset: str = "rst", active: int = 1) -> None:
    """Start a 10 ns clock and hold reset for 4 cycles."""
    clk = getattr(dut, clock)
    cocotb.start_soon(Clock(clk, 10, unit="ns").start())
    getattr(dut, reset).value = active
    await ClockCycles(clk, 4)
    getattr(dut, reset).value = 1 - active
    await RisingEdge(clk)


def pauses(rng: random.Random, busy: float) -> Any:
    """An endless pause pattern for cocotbext-axi: True (pause) with probability `busy`."""
    while True:
        yield rng.random() < busy


class VectorSink:
    """Collects packets from a stream whose tvalid/tready are vectors with one bit per lane.

    Args:
        dut: The design.
        prefix: Signal prefix (``m`` for ``m_tdata``, ``m_tvalid``...).
        lanes: Bits in the tvalid/tready vectors.
        width: tdata bits.
        rng: Drives random backpressure on every lane.
        busy: Probability that a lane's tready is low on a cycle.
    """

    def __init__(
        self, dut: Any, prefix: str, lanes: int, width: int, rng: random.Random, busy: float
    ) -> None:
        self.dut = dut
        self.prefix = prefix
        self.lanes = lanes
        self.width = width
        self.rng = rng
        self.busy = busy
        self.packets: list[list[bytes]] = [[] for _ in range(lanes)]
        self.null_beats = [0] * lanes
        self._partial = [bytearray() for _ in range(lanes)]
        cocotb.start_soon(self._run())

    def _signal(self, name: str) -> Any:
        return getattr(self.dut, f"{self.prefix}_{name}")

    async def _run(self) -> None:
        clk = self.dut.clk
        ready = self._signal("tready")
        lanes_bytes = self.width // 8
        while True:
            ready.value = sum(
                1 << lane for lane in range(self.lanes) if self.rng.random() >= self.busy
            )
            await RisingEdge(clk)
            moving = int(self._signal("tvalid").value) & int(ready.value)
            if not moving:
                continue
            assert moving & (moving - 1) == 0, f"two lanes valid at once: {moving:b}"
            lane = moving.bit_length() - 1
            data = int(self._signal("tdata").value).to_bytes(lanes_bytes, "little")
            keep = int(self._signal("tkeep").value)
            if keep == 0:
                self.null_beats[lane] += 1
            self._partial[lane] += bytes(data[i] for i in range(lanes_bytes) if keep >> i & 1)
            if int(self._signal("tlast").value):
                self.packets[lane].append(bytes(self._partial[lane]))
                self._partial[lane] = bytearray()
