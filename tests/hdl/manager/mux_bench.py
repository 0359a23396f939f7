"""cocotb bench of chunk_mux: publishers with random gaps and bubbles, a DMA with backpressure.

It records every cycle's requests, task ends, channel-ready and grants so that the pytest side
can replay them through the scheduler's cycle-exact model, and every chunk that came out.
"""

from __future__ import annotations

import json
import random
from dataclasses import dataclass, field
from pathlib import Path

import cocotb
from cocotb.triggers import ReadOnly, RisingEdge
from cocotbext.axi import AxiStreamBus, AxiStreamSink

from tests.support.axis_bench import bench_case, pauses, start


@dataclass
class Publisher:
    """One publisher converter as the mux sees it: messages cut into beats."""

    lanes: int
    messages: list[bytes]
    rng: random.Random
    bubble: float
    gap: int = 0
    message: int = 0
    offset: int = 0
    wait: int = 0
    presenting: bool = False
    sent: list[int] = field(default_factory=list)

    def beat(self) -> tuple[bool, bytes, int, bool, int]:
        """This cycle's (tvalid, data, keep, last, length)."""
        if self.message >= len(self.messages):
            return False, b"", 0, False, 0
        payload = self.messages[self.message]
        paused = self.wait > 0 or (self.offset and self.rng.random() < self.bubble)
        if not self.presenting and paused:
            return False, b"", 0, False, len(payload)
        self.presenting = True
        chunk = payload[self.offset : self.offset + self.lanes]
        keep = (1 << len(chunk)) - 1
        last = self.offset + self.lanes >= len(payload)
        return True, chunk.ljust(self.lanes, b"\0"), keep, last, len(payload)

    def clock(self, granted: bool) -> None:
        if self.wait > 0:
            self.wait -= 1
        if not granted:
            return
        self.presenting = False
        self.offset += self.lanes
        if self.offset >= len(self.messages[self.message]):
            self.message += 1
            self.offset = 0
            self.wait = self.rng.randrange(self.gap + 1)


@cocotb.test()
async def multiplexes_every_message(dut):
    case = bench_case()
    rng = random.Random(case["seed"])
    width = case["width"]
    lanes = width // 8
    # Inputs defined before reset ends: an undriven tvalid would leave 'U' in the scheduler.
    for name in ("s_tvalid", "s_tdata", "s_tkeep", "s_tlast", "s_length"):
        getattr(dut, name).value = 0
    await start(dut)
    sink = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m"), dut.clk, dut.rst)
    sink.set_pause_generator(pauses(rng, case["backpressure"]))
    publishers = [
        Publisher(lanes, [bytes.fromhex(m) for m in messages], rng, case["bubble"], case["gap"])
        for messages in case["messages"]
    ]
    trace = {"request": [], "last": [], "ready": [], "grant": []}
    for _ in range(case["max_cycles"]):
        if all(p.message >= len(p.messages) for p in publishers):
            break
        valid = data = keep = last = length = 0
        for index, publisher in enumerate(publishers):
            beat_valid, beat_data, beat_keep, beat_last, beat_length = publisher.beat()
            valid |= beat_valid << index
            data |= int.from_bytes(beat_data, "little") << (index * width)
            keep |= beat_keep << (index * lanes)
            last |= (beat_valid and beat_last) << index
            length |= beat_length << (index * 32)
        dut.s_tvalid.value = valid
        dut.s_tdata.value = data
        dut.s_tkeep.value = keep
        dut.s_tlast.value = last
        dut.s_length.value = length
        await ReadOnly()
        grant = int(dut.s_tready.value)
        trace["request"].append(valid)
        trace["last"].append(last)
        trace["ready"].append(int(getattr(dut, case["ready_signal"]).value))
        trace["grant"].append(grant)
        await RisingEdge(dut.clk)
        for index, publisher in enumerate(publishers):
            publisher.clock(bool(grant >> index & 1) and bool(valid >> index & 1))
    dut.s_tvalid.value = 0
    chunks, quiet = [], 0
    while quiet < 200:
        await RisingEdge(dut.clk)
        quiet = 0 if not sink.empty() or int(dut.m_tvalid.value) else quiet + 1
        while not sink.empty():
            chunks.append(bytes(sink.recv_nowait().tdata).hex())
    Path(case["result"]).write_text(json.dumps({"chunks": chunks, "trace": trace}))
    assert all(p.message >= len(p.messages) for p in publishers), "publishers did not finish"
