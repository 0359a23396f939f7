"""The ``sim`` transport: the build's logic co-simulated in GHDL behind the DMA interface.

`SimulatedLogic.start` runs GHDL (through cocotb's runner) in a child process on the VHDL that
``rfc build`` wrote (``hw/files.txt``, named by the plan relative to it), with
`rfc.runtime.sim_bridge` driving the logic's two DMA streams; the node and the simulation
exchange one transfer per datagram over a Unix ``SOCK_SEQPACKET`` socket, so the node's loop
is the one that runs on the board. As with the DMA, a write returns once the logic has taken
the transfer's last beat: the bridge then sends `TAKEN`, a one-byte datagram (every transfer is
at least a chunk header), which the reading side hands to the waiting writer. A logic that does
not take a transfer thus blocks the write, as a bitstream that does not answer blocks the DMA.
It needs GHDL and cocotb, not the compiler.
"""

from __future__ import annotations

import contextlib
import json
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import NotRequired, TypedDict

from rfc.errors import RfcError
from rfc.runtime.dma_device import FileDma
from rfc.runtime.plan import RuntimePlan

#: Seconds GHDL may take to analyse the logic and connect.
START_TIMEOUT = 600.0
#: VHDL standard of the generated logic.
VHDL_STANDARD = "08"
#: The datagram that says the logic took a whole PS→PL transfer.
TAKEN = b"\x06"


@dataclass
class SimulatedLogic:
    """`DmaChannels` whose other end is the logic simulated in GHDL.

    Attributes:
        channel: The transfers, one datagram each.
        connection: The socket to the simulation.
        process: The simulation.
        workdir: Its scratch folder (removed on close).
    """

    channel: FileDma
    connection: socket.socket
    process: subprocess.Popen[bytes]
    workdir: Path
    taken: threading.Semaphore = field(default_factory=lambda: threading.Semaphore(0))

    @classmethod
    def start(cls, plan: RuntimePlan, timeout: float = START_TIMEOUT) -> SimulatedLogic:
        """Analyse the build's logic in GHDL and connect to it.

        Raises:
            RfcError: The build holds no logic, GHDL or cocotb is missing, or the simulation
                ended before connecting.
        """
        job = _job(plan)
        workdir = Path(tempfile.mkdtemp(prefix="rfc-node-sim-"))
        address = str(workdir / "logic.sock")
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        listener.bind(address)
        listener.listen(1)
        listener.settimeout(0.5)
        job["socket"], job["build_dir"] = address, str(workdir / "ghdl")
        log = workdir / "simulation.log"
        with log.open("wb") as output:
            process = subprocess.Popen(
                [sys.executable, "-m", "rfc.runtime.sim_device", json.dumps(job)],
                stdout=output,
                stderr=subprocess.STDOUT,
            )
        deadline = time.monotonic() + timeout
        try:
            while True:
                try:
                    connection, _ = listener.accept()
                    break
                except TimeoutError:
                    if process.poll() is not None or time.monotonic() > deadline:
                        process.kill()
                        tail = log.read_text(errors="replace")[-2000:]
                        shutil.rmtree(workdir, ignore_errors=True)
                        raise RfcError(
                            f"the simulated logic did not start:\n{tail}",
                            hint="rebuild the system (rfc build) so that sw/ and hw/ agree",
                        ) from None
        finally:
            listener.close()
        return cls(
            FileDma(connection.fileno(), connection.fileno(), plan.max_transfer),
            connection,
            process,
            workdir,
        )

    def write(self, transfer: bytes) -> None:
        """Send one PS→PL transfer; return once the logic took its last beat (or on close)."""
        self.channel.write(transfer)
        self.taken.acquire()

    def read(self) -> bytes:
        """Receive one PL→PS transfer (b"" once closed); acknowledgements go to the writer."""
        while (transfer := self.channel.read()) == TAKEN:
            self.taken.release()
        return transfer

    def close(self) -> None:
        """End the simulation and remove its files (a blocked write returns)."""
        self.taken.release()
        with contextlib.suppress(OSError):
            self.connection.shutdown(socket.SHUT_RDWR)
        try:
            self.process.wait(10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self.connection.close()
        shutil.rmtree(self.workdir, ignore_errors=True)


class _Job(TypedDict):
    """What the child process simulates, as JSON on its command line."""

    sources: list[str]
    top: str
    clock_mhz: float
    socket: NotRequired[str]
    build_dir: NotRequired[str]


def _job(plan: RuntimePlan) -> _Job:
    if plan.logic is None:
        raise RfcError(
            "this build holds no logic to simulate (it was built with --no-hardware)",
            hint="rebuild without --no-hardware to try the node with --device sim",
        )
    if shutil.which("ghdl") is None:
        raise RfcError(
            "--device sim needs GHDL, which is not on the PATH",
            hint="install it (apt-get install ghdl)",
        )
    files = (plan.base / plan.logic.files).resolve()
    try:
        names = files.read_text().split()
    except OSError:
        raise RfcError(
            f"the logic's file list {files} is missing",
            hint="keep hw/ beside sw/ as rfc build wrote them",
        ) from None
    return {
        "sources": [str(files.parent / name) for name in names],
        "top": plan.logic.top,
        "clock_mhz": plan.logic.clock_mhz,
    }


def _simulate(job: _Job) -> None:
    """The child process: build the logic with GHDL and run the bridge until the node leaves."""
    from cocotb_tools.runner import get_runner

    build_dir = Path(job["build_dir"])
    flags = [f"--std={VHDL_STANDARD}", "-fsynopsys"]
    runner = get_runner("ghdl")
    sources = [Path(s) for s in job["sources"] if s.endswith((".vhd", ".vhdl"))]
    runner.build(
        sources=sources, hdl_toplevel=job["top"], build_dir=build_dir, build_args=flags, always=True
    )
    runner.test(
        test_module="rfc.runtime.sim_bridge",
        hdl_toplevel=job["top"],
        build_dir=build_dir,
        extra_env={"RFC_SIM_SOCKET": job["socket"], "RFC_SIM_CLOCK_MHZ": str(job["clock_mhz"])},
        test_args=flags,
    )


if __name__ == "__main__":
    _simulate(json.loads(sys.argv[1]))
