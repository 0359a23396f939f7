"""The runtime loop inside a cocotb simulation of the whole programmable logic (GHDL).

This module runs in the simulator's Python, started by `rfc.sim.hardware`. It reads the
job (a JSON file named by ``RFC_SIM_JOB``), compiles the spec, and replays the bag: messages
arrive at their recorded times on the simulated clock, wait in the processor's callback queues,
and go to the logic one DMA transfer at a time through a cocotbext-axi source on the PS→PL
stream (with random idle cycles); a sink on the PL→PS stream (with random backpressure) hands
each transfer to the runtime, which reassembles and routes it. Outputs of the logic take the
stamp of the newest input offered so far.

Idle time is skipped (`rfc.runtime.arrivals`): when nothing waits, nothing moves and the logic
has been quiet for the job's drain window (and is not still expected to answer a transfer,
`rfc.runtime.stall.AnswerWait`, nor busy by its ``busy`` bits, `rfc.sim.busy`), the next
message arrives at once. After the last
message the run ends once the system is idle the same way. A logic that stops completing
transfers while work is pending ends the run with the stall watchdog's report
(`rfc.runtime.stall`). Results go back through files: the published messages
(`rfc.runtime.records`), the account as JSON, the warnings of the busy bits, the progress
(messages offered so far), or the stall report instead.
"""

from __future__ import annotations

import json
import logging
import os
import random
from itertools import cycle
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, Event, SimTimeoutError, Timer, with_timeout
from cocotbext.axi import AxiStreamBus, AxiStreamSink, AxiStreamSource

from rfc.driver import compile_spec
from rfc.lib.converters.malformed import DROP_REASONS, status_port
from rfc.lower.runtime_plan import DesignPlan
from rfc.messages.rosbags_adapter import message_types, read_bag
from rfc.runtime.arrivals import IDLE_FRACTION, ArrivalClock
from rfc.runtime.core import Published, QueueConfig, QueuePolicy, Runtime
from rfc.runtime.protocol import Chunk
from rfc.runtime.records import write_records
from rfc.runtime.stall import AnswerWait, StallError, StallWatch, largest_output, pending_work
from rfc.runtime.status import decode_status, is_status, status_request
from rfc.runtime.stream_top import BusyTop, StreamTop
from rfc.sim.busy import BusyWatch
from rfc.sim.hardware import CosimJob


class _Replay:
    def __init__(self, dut: StreamTop, job: CosimJob, plan: DesignPlan, runtime: Runtime) -> None:
        self.job = job
        self.plan = plan
        self.runtime = runtime
        self.clock = dut.aclk
        self.period_ns = 1000.0 / job["clock_mhz"]
        self.stamp = 0
        self.published: list[Published] = []
        self.work = Event()
        self.sending: Chunk | None = None
        self.received_transfers = 0
        self.status_read = Event()
        self.watch = StallWatch(
            job["stall_cycles"], len(dut.s_axis_mm2s_tkeep), largest_output(runtime)
        )
        self.answer = AnswerWait(len(dut.s_axis_mm2s_tkeep))
        self.busy_port = dut.busy if isinstance(dut, BusyTop) else None
        names = tuple(job["busy"]) if self.busy_port is not None else ()
        self.busy_bits = BusyWatch(names, job["stall_cycles"])
        self.working = False
        self.source = AxiStreamSource(
            AxiStreamBus.from_prefix(dut, "s_axis_mm2s"),
            dut.aclk,
            dut.aresetn,
            reset_active_level=False,
        )
        self.sink = AxiStreamSink(
            AxiStreamBus.from_prefix(dut, "m_axis_s2mm"),
            dut.aclk,
            dut.aresetn,
            reset_active_level=False,
        )
        chance = random.Random(job["seed"])
        pattern = [chance.random() < IDLE_FRACTION for _ in range(1021)]
        self.source.set_pause_generator(cycle(pattern))
        self.sink.set_pause_generator(cycle(pattern[::-1]))

    def cycles(self) -> int:
        return int(cocotb.utils.get_sim_time("ns") / self.period_ns)

    async def send(self) -> None:
        """The PS→PL DMA: one transfer at a time, the software scheduler choosing."""
        while True:
            chosen = self.runtime.next_transfer()
            if chosen is None:
                self.sending = None
                self.work.clear()
                await self.work.wait()
                continue
            chunk, _ = chosen
            self.sending = chunk
            await self.source.send(chunk.to_bytes())
            await self.source.wait()
            self.watch.completed(self.cycles(), chunk.size)
            self.busy_bits.completed(self.cycles())
            self.answer.sent(self.cycles(), chunk.size)

    async def receive(self) -> None:
        """The PL→PS DMA: every transfer to the runtime."""
        while True:
            frame = await self.sink.recv()
            self.received_transfers += 1
            self.watch.completed(self.cycles(), len(frame.tdata))
            self.busy_bits.completed(self.cycles())
            if is_status(bytes(frame.tdata)):
                names = self.runtime.plan.subscriber_names
                self.runtime.logic_drops(decode_status(bytes(frame.tdata), names))
                self.status_read.set()
                continue
            self.answer.answered()
            self.published += self.runtime.receive(bytes(frame.tdata), self.stamp, self.cycles())
            if self.runtime.waiting():
                self.work.set()

    def busy(self) -> bool:
        return (
            self.sending is not None
            or self.runtime.waiting() > 0
            or not self.source.idle()
            or self.receiving()
            or self.runtime.in_flight()
        )

    async def run_until(self, due: int) -> None:
        """Run the clock to cycle `due`, or less when the system falls idle before it.

        Raises:
            StallError: Work is pending and no transfer completes (the logic stalls).
        """
        drain = self.job["drain_cycles"]
        while self.cycles() < due:
            before = self.received_transfers
            step = min(drain, due - self.cycles())
            await Timer(step * self.period_ns, unit="ns")
            busy = self.busy()
            settled = not self.working  # a whole quiet window after the busy bits fell
            self.working = self.logic_working()
            quiet = settled and not self.working and self.received_transfers == before
            if not busy and quiet and not self.answer.awaiting(self.cycles()):
                return
            sending = self.sending.size if self.sending is not None else 0
            self.watch.check(self.cycles(), busy, self.pending, sending, self.receiving())

    def logic_working(self) -> bool:
        """Whether the logic's busy bits say it still works (a top without them: never)."""
        if self.busy_port is None or not self.busy_bits.names:
            return False
        return self.busy_bits.busy(self.cycles(), int(self.busy_port.value))

    def receiving(self) -> bool:
        return bool(self.sink.active) or not self.sink.empty()

    def pending(self) -> str:
        return pending_work(self.runtime, self.sending, self.receiving())

    async def replay(self) -> None:
        types = message_types(
            self.plan.types.middleware,
            self.plan.types.distro,
            tuple(str(p) for p in self.plan.design.project.msg_paths),
            (self.job["bag"],),
        )
        progress = Path(self.job["progress"])
        arrivals = ArrivalClock(self.job["clock_mhz"])
        for count, message in enumerate(read_bag(self.job["bag"], types, self.job["topics"]), 1):
            due = arrivals.due(message.timestamp_ns)
            await self.run_until(due)
            arrivals.offered(self.cycles(), due)
            self.stamp = message.timestamp_ns
            self.published += self.runtime.offer(
                self.runtime_topic(message.topic), message.data, self.stamp, self.cycles()
            )
            self.work.set()
            if count % 16 == 0:
                progress.write_text(str(count))
        await self.run_until(1 << 62)
        self.runtime.finish()

    async def read_status(self) -> None:
        """Ask the logic for its drop counters through the DMA, as the node does.

        Raises:
            StallError: The logic does not answer.
        """
        await self.source.send(status_request().to_bytes())
        try:
            await with_timeout(
                self.status_read.wait(), self.job["stall_cycles"] * self.period_ns, "ns"
            )
        except SimTimeoutError:
            raise StallError(
                "the logic did not answer the request for its drop counters",
                hint="rebuild the system: logic built before rfc read the counters lacks it",
            ) from None

    def runtime_topic(self, topic: str) -> str:
        return self.job["topic_names"].get(topic, topic)


@cocotb.test()
async def replay_through_logic(dut: StreamTop) -> None:
    """Replay the job's bag through the simulated logic and write the results."""
    for name in ("cocotb.echo_top", "cocotb"):
        logging.getLogger(name).setLevel(logging.WARNING)
    job: CosimJob = json.loads(Path(os.environ["RFC_SIM_JOB"]).read_text())
    design = compile_spec(job["spec"])
    queues = QueueConfig(QueuePolicy(job["policy"]), job["depth"])
    plan = DesignPlan(design)
    runtime = Runtime(plan, queues, screen=job["screen"])
    Clock(dut.aclk, 1000.0 / job["clock_mhz"], unit="ns").start()
    dut.aresetn.value = 0
    await ClockCycles(dut.aclk, 4)
    dut.aresetn.value = 1
    await ClockCycles(dut.aclk, 2)
    # The streams' drivers start after the reset: a synthesized netlist's registers have no
    # value before it.
    replay = _Replay(dut, job, plan, runtime)
    cocotb.start_soon(replay.send())
    cocotb.start_soon(replay.receive())
    try:
        await replay.replay()
        if hasattr(dut, status_port(0, DROP_REASONS[0])):  # a hand-written test top has none
            await replay.read_status()
    except StallError as exc:
        Path(job["stalled"]).write_text(json.dumps({"message": exc.message, "hint": exc.hint}))
        return
    Path(job["warnings"]).write_text(json.dumps(replay.busy_bits.warnings))
    write_records(Path(job["results"]), replay.published)
    Path(job["account"]).write_text(json.dumps(replay.runtime.account.to_json()))
