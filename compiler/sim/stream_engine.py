"""Replay a bag through Verilated logic whose DMA streams are driven in C++, not by cocotb.

The cocotb harness (`rfc.sim.cosim`) runs Python on every clock cycle: its drivers move one
beat at a time and cost far more than the logic itself. Here the testbench
``testbench/axis_engine.cpp`` (built by `rfc.toolchain.verilator.build_stream_engine`) moves the
beats, idles the PS→PL stream and holds back the PL→PS stream with the same seeded pattern,
and stops only when Python must act: when the PS→PL transfer completes while another message
waits, or a PL→PS transfer completes whose message may come back to the logic; other
transfers are handed over, with the cycle they completed at, when it stops. The processor
side — queues, software scheduler, reassembly, software accelerators, the account — stays in
`Runtime`, called once per transfer, with the same rules as the cocotb harness: arrivals at
their recorded times with idle skipped (`rfc.runtime.arrivals`), the stall watchdog and the
wait for answers (`rfc.runtime.stall`), the logic's ``busy`` bits (`rfc.sim.busy`, read with
the status registers), outputs stamped with the newest input offered so far.
"""

from __future__ import annotations

import random
import re
import struct
import subprocess
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from rfc.lib.converters.malformed import DROP_REASONS, status_port
from rfc.messages.rosbags_adapter import BagMessage
from rfc.runtime.arrivals import IDLE_FRACTION, ArrivalClock
from rfc.runtime.core import Published, Runtime
from rfc.runtime.plan import ToTopic
from rfc.runtime.protocol import Chunk
from rfc.runtime.stall import AnswerWait, StallWatch, largest_output, pending_work
from rfc.sim.busy import BusyWatch
from rfc.sim.settings import ReplaySettings
from rfc.toolchain.verilator import build_stream_engine

#: The engine's C++ source.
TESTBENCH = Path(__file__).resolve().parent / "testbench" / "axis_engine.cpp"
#: Cycles the engine spends in and out of reset before the drivers start (as the cocotb harness).
RESET_CYCLES = 6
#: The top level's port of busy bits (`rfc.lower.system.busy`).
BUSY = "busy"
#: Length of the repeated idle/backpressure pattern.
PATTERN_LENGTH = 1021

_STEP = struct.Struct("<QBQI")
_FRAME = struct.Struct("<QI")
#: What `StreamEngine.run` stops at, and the flags of its answer.
SENT, RECEIVED, _RECEIVING = 1, 2, 4


def pause_pattern(seed: int) -> bytes:
    """One byte per cycle, 1 when the PS→PL stream idles (the PL→PS sink reads it backwards)."""
    chance = random.Random(seed)
    return bytes(chance.random() < IDLE_FRACTION for _ in range(PATTERN_LENGTH))


def status_registers(subscribers: Iterable[int], top_verilog: str) -> dict[str, tuple[int, str]]:
    """The drop counters the top level has: port name → (subscriber id, reason label)."""
    return {
        status_port(subscriber, reason): (subscriber, reason.label)
        for subscriber in subscribers
        for reason in DROP_REASONS
        if re.search(rf"\b{status_port(subscriber, reason)}\b", top_verilog)
    }


class VerilogTop(Protocol):
    """The logic to simulate: its top module, its Verilog in compile order, its bus width."""

    top: str
    verilog: Sequence[Path]
    bus_width: int


@dataclass(frozen=True)
class Step:
    """What the engine reports after running.

    Attributes:
        cycles: Cycles run.
        sent_at: The cycle of the run (from 1) at which the PS→PL transfer completed, or None.
        received: The PL→PS transfers that completed, each with the cycle of the run it did.
        receiving: Whether a PL→PS transfer is under way.
    """

    cycles: int
    sent_at: int | None
    received: tuple[tuple[int, bytes], ...]
    receiving: bool


class StreamEngine:
    """The compiled testbench as a child process, spoken to through its standard streams.

    Args:
        binary: The engine built for the logic.
        seed: Seed of the idle/backpressure pattern.
    """

    def __init__(self, binary: Path, seed: int) -> None:
        self._process = subprocess.Popen(
            [str(binary)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, bufsize=0
        )
        assert self._process.stdin is not None
        assert self._process.stdout is not None
        self._in = self._process.stdin
        self._out = self._process.stdout
        pattern = pause_pattern(seed)
        self._pending = bytearray(struct.pack("<I", len(pattern)) + pattern)

    def send(self, transfer: bytes) -> None:
        """Queue one PS→PL transfer (written with the next command)."""
        self._pending += b"S" + struct.pack("<I", len(transfer)) + transfer

    def run(self, cycles: int, stop: int) -> Step:
        """Run at most `cycles` cycles, or until a transfer of a kind `stop` names completes.

        Args:
            cycles: The most cycles to run.
            stop: `SENT` (the PS→PL transfer), `RECEIVED` (a PL→PS transfer), both or 0.
        """
        self._write(b"R" + struct.pack("<QB", cycles, stop))
        ran, flags, sent_at, count = _STEP.unpack(self._read(_STEP.size))
        frames = []
        for _ in range(count):
            at, size = _FRAME.unpack(self._read(_FRAME.size))
            frames.append((at, self._read(size)))
        return Step(ran, sent_at if flags & SENT else None, tuple(frames), bool(flags & _RECEIVING))

    def registers(self) -> list[int]:
        """The status registers' values now, in the order the engine was built with."""
        self._write(b"P")
        return self._registers()

    def finish(self) -> list[int]:
        """End the run; the status registers' values in the order the engine was built with."""
        self._write(b"Q")
        values = self._registers()
        self._process.wait()
        return values

    def _registers(self) -> list[int]:
        (count,) = struct.unpack("<I", self._read(4))
        return list(struct.unpack(f"<{count}Q", self._read(8 * count)))

    def close(self) -> None:
        """Stop the child process if it still runs."""
        if self._process.poll() is None:
            self._process.kill()
            self._process.wait()
        self._in.close()
        self._out.close()

    def _write(self, command: bytes) -> None:
        data = memoryview(bytes(self._pending) + command)
        self._pending.clear()
        while data:  # a raw pipe may take a large transfer in parts
            data = data[self._in.write(data) :]

    def _read(self, size: int) -> bytes:
        data = bytearray()
        while len(data) < size:  # a pipe hands over large transfers in parts
            part = self._out.read(size - len(data))
            if not part:
                status = self._process.poll()
                raise EngineError(f"the stream engine ended early (exit status {status})")
            data += part
        return bytes(data)


class EngineError(RuntimeError):
    """The engine process died: a bug in rfc, not in the user's input."""


class EngineReplay:
    """The replay loop of the cocotb harness, at transfer granularity.

    Args:
        engine: The running engine.
        runtime: The processor side.
        clock_mhz: The logic's clock.
        lanes: Bytes per beat of the DMA streams.
        settings: The replay settings.
        busy: The logic's ``busy`` bits, or None when its top level has none.
    """

    # Keeps its collaborators and the replay's state: like the converters' defaults in shape only.
    def __init__(
        self,
        engine: StreamEngine,
        runtime: Runtime,
        clock_mhz: float,
        lanes: int,
        settings: ReplaySettings,
        busy: BusyWatch | None = None,
    ) -> None:
        self.engine = engine
        self.runtime = runtime
        self.clock_mhz = clock_mhz
        self.settings = settings
        self.cycle = RESET_CYCLES
        self.stamp = 0
        self.published: list[Published] = []
        self.sending: Chunk | None = None
        self.receiving = False
        self.watch = StallWatch(settings.stall_cycles, lanes, largest_output(runtime))
        self.answer = AnswerWait(lanes)
        self.busy = busy
        self.working = False
        # whether a PL→PS transfer may cause a PS→PL one (through software, or directly)
        self.feedback = any(
            not isinstance(route, ToTopic)
            for routes in runtime.plan.logic_outputs.values()
            for route in routes
        )

    def replay(self, messages: Iterable[BagMessage]) -> list[Published]:
        """Offer every message at its recorded time, run until idle, finish the account.

        Raises:
            StallError: The logic stopped completing transfers while work was pending.
        """
        arrivals = ArrivalClock(self.clock_mhz)
        for count, message in enumerate(messages, 1):
            due = arrivals.due(message.timestamp_ns)
            self.run_until(due)
            arrivals.offered(self.cycle, due)
            self.stamp = message.timestamp_ns
            self.published += self.runtime.offer(
                message.topic, message.data, self.stamp, self.cycle
            )
            self._send_next()
            if self.settings.progress is not None and count % 16 == 0:
                self.settings.progress(count)
        self.run_until(1 << 62)
        self.runtime.finish()
        return self.published

    def run_until(self, due: int) -> None:
        """Run to cycle `due`, or less when the system falls idle before it."""
        while self.cycle < due:
            received = self._run(min(self.settings.drain_cycles, due - self.cycle))
            busy = self._busy()
            # a whole quiet window after the logic's busy bits fell
            settled = not self.working
            self.working = self._working()
            quiet = settled and not self.working and not received
            if not busy and quiet and not self.answer.awaiting(self.cycle):
                return
            sending = self.sending.size if self.sending is not None else 0
            self.watch.check(self.cycle, busy, self._pending, sending, self.receiving)

    def _run(self, cycles: int) -> bool:
        """Run `cycles` cycles, answering every completed transfer; whether any PL→PS did.

        The engine stops when the PS→PL transfer completes only while another waits, and when
        a PL→PS transfer completes only if what it carries may come back to the logic: other
        transfers are answered in order when it stops.
        """
        received = False
        while cycles > 0:
            stop = (SENT if self.runtime.waiting() else 0) | (RECEIVED if self.feedback else 0)
            step = self.engine.run(cycles, stop)
            events = [(at, None) for at in (step.sent_at,) if at is not None]
            for at, data in sorted([*events, *step.received], key=lambda event: event[0]):
                if data is None:
                    assert self.sending is not None
                    self.watch.completed(self.cycle + at, self.sending.size)
                    self._moved(self.cycle + at)
                    self.answer.sent(self.cycle + at, self.sending.size)
                    self.sending = None
                else:
                    received = True
                    self.watch.completed(self.cycle + at, len(data))
                    self._moved(self.cycle + at)
                    self.answer.answered()
                    now = self.cycle + at
                    self.published += self.runtime.receive(data, self.stamp, now)
            cycles -= step.cycles
            self.cycle += step.cycles
            self.receiving = step.receiving
            self._send_next()
        return received

    def _send_next(self) -> None:
        """The PS→PL DMA: the software scheduler's next transfer once the last one is done."""
        if self.sending is not None:
            return
        chosen = self.runtime.next_transfer()
        if chosen is not None:
            self.sending = chosen[0]
            self.engine.send(self.sending.to_bytes())

    def _busy(self) -> bool:
        return (
            self.sending is not None
            or self.runtime.waiting() > 0
            or self.receiving
            or self.runtime.in_flight()
        )

    def _pending(self) -> str:
        return pending_work(self.runtime, self.sending, self.receiving)

    def _moved(self, cycle: int) -> None:
        if self.busy is not None:
            self.busy.completed(cycle)

    def _working(self) -> bool:
        """Whether the logic's busy bits say it still works (the last status register)."""
        if self.busy is None:
            return False
        return self.busy.busy(self.cycle, self.engine.registers()[-1])


def build_engine(
    top: VerilogTop, subscribers: Iterable[int]
) -> tuple[Path, dict[str, tuple[int, str]]]:
    """The stream engine of `top` (compiled once per content) and the drop counters it reads.

    The engine reads the top's ``busy`` port after the drop counters, when it has one.

    Raises:
        VerilatorError: The engine cannot be built.
    """
    verilog = [Path(path) for path in top.verilog]
    module = re.compile(rf"\bmodule\s+{re.escape(top.top)}\b")
    top_text = next((t for p in verilog if module.search(t := p.read_text())), "")
    registers = status_registers(subscribers, top_text)
    ports = [*registers, *((BUSY,) if _busy_names(top) else ())]
    binary = build_stream_engine(TESTBENCH, verilog, top.top, top.bus_width // 8, ports)
    return binary, registers


def _busy_names(top: VerilogTop) -> tuple[str, ...]:
    """The blocks the top's ``busy`` bits watch (none for a top without the port)."""
    return tuple(getattr(top, "busy", ()))


def simulate_with_engine(
    runtime: Runtime,
    messages: Iterable[BagMessage],
    top: VerilogTop,
    *,
    clock_mhz: float,
    settings: ReplaySettings,
) -> list[Published]:
    """Replay `messages` through the Verilog of `top` in the stream engine.

    Args:
        runtime: The processor side (its account is completed, the logic's drops included).
        messages: Input messages in time order, on the spec's topics.
        top: The logic's top level with its ``verilog`` files in compile order.
        clock_mhz: The logic's clock (message arrivals convert to its cycles).
        settings: The replay settings.

    Returns:
        Everything published, in order.

    Raises:
        StallError: The logic stalled.
        VerilatorError: The engine cannot be built.
        EngineError: The engine died.
    """
    binary, registers = build_engine(top, runtime.plan.subscriber_names)
    lanes = top.bus_width // 8
    engine = StreamEngine(binary, settings.seed)
    try:
        names = _busy_names(top)
        busy = BusyWatch(names, settings.stall_cycles) if names else None
        loop = EngineReplay(engine, runtime, clock_mhz, lanes, settings, busy)
        published = loop.replay(messages)
        values = engine.finish()[: len(registers)]
    finally:
        engine.close()
    if busy is not None and settings.warnings is not None:
        settings.warnings.extend(busy.warnings)
    runtime.logic_drops(dict(zip(registers.values(), values, strict=True)))
    return published
