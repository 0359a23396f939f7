"""The simulator's end of the ``sim`` transport: datagrams in, AXI-Stream transfers out.

Runs inside cocotb (started by `rfc.runtime.sim_device`): every datagram from the node is one
PS→PL transfer on ``s_axis_mm2s``, acknowledged with `rfc.runtime.sim_device.TAKEN` once the
logic has taken its last beat; every PL→PS transfer from ``m_axis_s2mm`` goes back as one
datagram. The clock runs while anything moves; once the logic has been quiet a while, the
bridge waits for the node in wall time (the logic is idle, nothing is lost) between short runs.
The test ends when the node closes the socket.
"""

from __future__ import annotations

import logging
import os
import select
import socket

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles
from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamSink, AxiStreamSource

from rfc.runtime.sim_device import TAKEN
from rfc.runtime.stream_top import StreamTop

#: Cycles simulated between two looks at the socket.
STEP_CYCLES = 16
#: Quiet steps after which the bridge waits for the node in wall time.
QUIET_STEPS = 64
#: Seconds of one such wait.
WAIT_SECONDS = 0.02


@cocotb.test()
async def bridge(dut: StreamTop) -> None:
    """Move transfers between the node's socket and the logic until the node leaves."""
    logging.getLogger("cocotb").setLevel(logging.WARNING)
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    connection.connect(os.environ["RFC_SIM_SOCKET"])
    period_ns = 1000.0 / float(os.environ["RFC_SIM_CLOCK_MHZ"])
    Clock(dut.aclk, period_ns, unit="ns").start()
    source = AxiStreamSource(
        AxiStreamBus.from_prefix(dut, "s_axis_mm2s"),
        dut.aclk,
        dut.aresetn,
        reset_active_level=False,
    )
    sink = AxiStreamSink(
        AxiStreamBus.from_prefix(dut, "m_axis_s2mm"),
        dut.aclk,
        dut.aresetn,
        reset_active_level=False,
    )
    dut.aresetn.value = 0
    await ClockCycles(dut.aclk, 4)
    dut.aresetn.value = 1
    await ClockCycles(dut.aclk, 2)
    quiet = 0
    while True:
        moved = False
        wait = WAIT_SECONDS if quiet > QUIET_STEPS else 0
        while select.select([connection], [], [], wait)[0]:
            transfer = connection.recv(1 << 24)
            if not transfer:
                connection.close()
                return
            taken = AxiStreamFrame(transfer, tx_complete=lambda _: connection.send(TAKEN))
            await source.send(taken)
            moved, wait = True, 0
        while not sink.empty():
            connection.send(bytes(sink.recv_nowait().tdata))
            moved = True
        busy = moved or not source.idle() or bool(sink.active)
        quiet = 0 if busy else quiet + 1
        await ClockCycles(dut.aclk, STEP_CYCLES)
