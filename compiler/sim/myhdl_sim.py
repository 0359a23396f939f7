"""Simulated hardware in MyHDL: the same replay as `rfc.sim.cosim`, for logic written in MyHDL.

Where the whole logic is a MyHDL design (its top provider gives a ``myhdl`` block factory that
takes the contract's port signals by name), it runs in MyHDL's own simulator, in this process:
no GHDL, no files. One clocked process plays the processor: it samples both AXI-Stream
handshakes at each rising edge, offers messages as they arrive (`rfc.runtime.arrivals`), drives
the PS→PL stream with the software scheduler's next chunk (with random idle cycles between
beats) and takes PL→PS beats with random backpressure; quiet cycles count only while the logic's
``busy`` bits (where its top has them, `rfc.sim.busy`) are low. Same seed, same runtime,
same account as the GHDL backend; the cycle-level timing of the two testbenches differs slightly.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from myhdl import ResetSignal, Signal, StopSimulation, block, delay, instance, intbv

from rfc.messages.rosbags_adapter import BagMessage
from rfc.runtime.arrivals import IDLE_FRACTION, ArrivalClock
from rfc.runtime.core import Published, Runtime
from rfc.runtime.protocol import Chunk
from rfc.runtime.stall import StallWatch, largest_output, pending_work
from rfc.sim.busy import BusyWatch
from rfc.sim.settings import ReplaySettings
from rfc.toolchain.myhdl_state import elaboration, transient_signals

MyhdlFactory = Callable[..., Any]


def _beats(transfer: bytes, lanes: int) -> list[tuple[int, int, bool]]:
    """(data, keep, last) of each beat of one transfer, little-endian."""
    beats = []
    for start in range(0, len(transfer), lanes):
        piece = transfer[start : start + lanes]
        last = start + lanes >= len(transfer)
        beats.append((int.from_bytes(piece, "little"), (1 << len(piece)) - 1, last))
    return beats


# MyHDL would otherwise keep the replay's signals, and reset them after every later run.
@transient_signals()
def simulate_with_myhdl(
    factory: MyhdlFactory,
    bus_width: int,
    runtime: Runtime,
    messages: Iterable[BagMessage],
    *,
    clock_mhz: float,
    settings: ReplaySettings,
    busy: tuple[str, ...] = (),
) -> list[Published]:
    """Replay `messages` (spec topics, time order) through the MyHDL logic; finish the account.

    Args:
        factory: Elaborates the logic from the contract's port signals, by name.
        bus_width: Bits of the DMA streams.
        runtime: The processor side.
        messages: Input messages in time order, on the spec's topics.
        clock_mhz: The logic's clock.
        settings: The replay settings.
        busy: The blocks the logic's ``busy`` port watches (none: it has no such port).

    Raises:
        StallError: The logic stalled (`rfc.runtime.stall`).
    """
    lanes = bus_width // 8
    ports: dict[str, Any] = {
        "aclk": Signal(bool(0)),
        "aresetn": ResetSignal(0, active=0, isasync=False),
        "s_axis_mm2s_tdata": Signal(intbv(0)[bus_width:]),
        "s_axis_mm2s_tkeep": Signal(intbv(0)[lanes:]),
        "s_axis_mm2s_tvalid": Signal(bool(0)),
        "s_axis_mm2s_tready": Signal(bool(0)),
        "s_axis_mm2s_tlast": Signal(bool(0)),
        "m_axis_s2mm_tdata": Signal(intbv(0)[bus_width:]),
        "m_axis_s2mm_tkeep": Signal(intbv(0)[lanes:]),
        "m_axis_s2mm_tvalid": Signal(bool(0)),
        "m_axis_s2mm_tready": Signal(bool(0)),
        "m_axis_s2mm_tlast": Signal(bool(0)),
    }
    if busy:
        ports["busy"] = Signal(intbv(0)[len(busy) :])
    processor = _Processor(ports, lanes, runtime, iter(messages), clock_mhz, settings, busy)

    @block
    def bench() -> Any:
        logic = factory(**ports)

        @instance
        def clock() -> Iterator[Any]:
            half = 1
            while True:
                yield delay(half)
                ports["aclk"].next = not ports["aclk"]

        @instance
        def drive() -> Iterator[Any]:
            yield from processor.run()

        return logic, clock, drive

    with elaboration():  # MyHDL's own elaboration reads the source context of every caller
        bench().run_sim(quiet=1)
    if settings.warnings is not None:
        settings.warnings.extend(processor.busy.warnings)
    runtime.finish()
    return processor.published


class _Processor:
    """The processor side of the testbench, one rising edge at a time."""

    def __init__(
        self,
        ports: dict[str, Any],
        lanes: int,
        runtime: Runtime,
        messages: Iterator[BagMessage],
        clock_mhz: float,
        settings: ReplaySettings,
        busy: tuple[str, ...],
    ) -> None:
        self.ports = ports
        self.lanes = lanes
        self.runtime = runtime
        self.messages = messages
        self.arrivals = ArrivalClock(clock_mhz)
        self.settings = settings
        self.chance = random.Random(settings.seed)
        self.published: list[Published] = []
        self.beats: list[tuple[int, int, bool]] = []
        self.sending: Chunk | None = None
        self.watch = StallWatch(settings.stall_cycles, lanes, largest_output(runtime))
        self.busy = BusyWatch(busy, settings.stall_cycles)
        self.received = bytearray()
        self.stamp = 0
        self.cycle = 0
        self.quiet = 0
        self.offered = 0

    def run(self) -> Iterator[Any]:
        p = self.ports
        for _ in range(4):
            yield p["aclk"].posedge
        p["aresetn"].next = 1
        upcoming = next(self.messages, None)
        while True:
            yield p["aclk"].posedge
            self.cycle += 1
            moved = self._sample()
            busy = bool(
                self.beats
                or self.runtime.waiting()
                or self.received
                or self.runtime.in_flight()
                or p["m_axis_s2mm_tvalid"]
            )
            working = bool(self.busy.names) and self.busy.busy(self.cycle, int(p["busy"]))
            self.quiet = 0 if busy or moved or working else self.quiet + 1
            sending = self.sending.size if self.sending is not None else 0
            self.watch.check(self.cycle, busy, self._pending, sending, self._receiving())
            drain = self.settings.drain_cycles
            if upcoming is None and self.quiet >= drain:
                raise StopSimulation
            while upcoming is not None:  # every message due by now, together
                due = self.arrivals.due(upcoming.timestamp_ns)
                if self.cycle < due and self.quiet < drain:
                    break
                self.arrivals.offered(self.cycle, due)
                self._offer(upcoming)
                upcoming = next(self.messages, None)
            self._drive()

    def _offer(self, message: BagMessage) -> None:
        self.stamp = message.timestamp_ns
        self.published += self.runtime.offer(message.topic, message.data, self.stamp, self.cycle)
        self.offered += 1
        self.quiet = 0
        if self.settings.progress is not None:
            self.settings.progress(self.offered)

    def _sample(self) -> bool:
        """Take the beats that moved on this edge; return whether any did."""
        p = self.ports
        moved = False
        if p["s_axis_mm2s_tvalid"] and p["s_axis_mm2s_tready"]:
            self.beats.pop(0)
            moved = True
            if not self.beats and self.sending is not None:
                self.watch.completed(self.cycle, self.sending.size)
                self.busy.completed(self.cycle)
                self.sending = None
        if p["m_axis_s2mm_tvalid"] and p["m_axis_s2mm_tready"]:
            keep = int(p["m_axis_s2mm_tkeep"])
            data = int(p["m_axis_s2mm_tdata"]).to_bytes(self.lanes, "little")
            self.received += bytes(b for i, b in enumerate(data) if keep >> i & 1)
            moved = True
            if p["m_axis_s2mm_tlast"]:
                transfer, self.received = bytes(self.received), bytearray()
                self.watch.completed(self.cycle, len(transfer))
                self.busy.completed(self.cycle)
                self.published += self.runtime.receive(transfer, self.stamp, self.cycle)
        return moved

    def _receiving(self) -> bool:
        return bool(self.received) or bool(self.ports["m_axis_s2mm_tvalid"])

    def _pending(self) -> str:
        return pending_work(self.runtime, self.sending, self._receiving())

    def _drive(self) -> None:
        p = self.ports
        if not self.beats and (chosen := self.runtime.next_transfer()) is not None:
            self.sending = chosen[0]
            self.beats = _beats(self.sending.to_bytes(), self.lanes)
        presenting = bool(p["s_axis_mm2s_tvalid"]) and not p["s_axis_mm2s_tready"]
        if self.beats and (presenting or self.chance.random() >= IDLE_FRACTION):
            data, keep, last = self.beats[0]
            p["s_axis_mm2s_tdata"].next = data
            p["s_axis_mm2s_tkeep"].next = keep
            p["s_axis_mm2s_tlast"].next = last
            p["s_axis_mm2s_tvalid"].next = True
        else:
            p["s_axis_mm2s_tvalid"].next = False
        p["m_axis_s2mm_tready"].next = self.chance.random() >= IDLE_FRACTION
