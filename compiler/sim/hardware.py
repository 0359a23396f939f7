"""Simulated hardware: replay a bag through the whole programmable logic in GHDL.

The logic comes from a *top provider* — by default `rfc.lower.hardware.simulation_top`, the
whole-system generation — a function ``(design, directory) -> top`` whose result has ``top``
(the entity), ``sources`` (VHDL in compile order) and ``bus_width``; the entity has the ports
of the system contract (docs/runtime.md). The replay itself runs in the simulator
(`rfc.sim.cosim`); this module prepares its job, runs cocotb in a worker thread while
reporting progress, and reads the results back. GHDL runs the logic on its fastest installed
back-end: llvm (or gcc) compiles it to a program once per content of its VHDL, which later
runs reuse from the cache (`rfc.toolchain.cocotb_sim.CompiledLogic`).
"""

from __future__ import annotations

import importlib
import json
import os
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol, TypedDict

from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.runtime.account import Account
from rfc.runtime.core import Published, QueueConfig
from rfc.runtime.records import read_records
from rfc.runtime.stall import StallError
from rfc.sim.settings import DEFAULT_SETTINGS, ReplaySettings
from rfc.toolchain import CosimError, run_cocotb
from rfc.toolchain.cocotb_sim import CompiledLogic, compile_logic, compiled_logic
from rfc.toolchain.ghdl import fastest_backend

#: The top provider of the whole-system hardware generation.
DEFAULT_TOP_PROVIDER = "rfc.lower.hardware:simulation_top"


class SimulationTop(Protocol):
    """The logic to simulate: its entity, its VHDL sources in compile order, its bus width.

    A top may also name the blocks its ``busy`` port watches (``busy``, `rfc.sim.busy`).
    """

    top: str
    sources: list[Path]
    bus_width: int


TopProvider = Callable[[Design, Path], SimulationTop]


class CosimJob(TypedDict):
    """What the harness in the simulator (`rfc.sim.cosim`) reads: the replay and its files."""

    spec: str
    bag: str
    topics: list[str]
    topic_names: dict[str, str]
    clock_mhz: float
    policy: str
    depth: int
    screen: bool
    drain_cycles: int
    stall_cycles: int
    seed: int
    results: str
    account: str
    progress: str
    stalled: str
    busy: list[str]
    warnings: str


def load_top_provider(reference: str = DEFAULT_TOP_PROVIDER) -> TopProvider:
    """Import a top provider named ``module:function``.

    Raises:
        RfcError: It cannot be imported (for the default: this rfc has no whole-system
            hardware generation yet).
    """
    module_name, _, function_name = reference.partition(":")
    try:
        provider: TopProvider = getattr(importlib.import_module(module_name), function_name)
    except (ImportError, AttributeError):
        if reference == DEFAULT_TOP_PROVIDER:
            raise RfcError(
                "simulating the logic needs the whole-system hardware generation "
                f"({DEFAULT_TOP_PROVIDER}), which this installation of rfc lacks",
                hint="switch the hardware accelerators to ROS-SW to replay in software",
            ) from None
        raise RfcError(
            f"cannot import top provider '{reference}'",
            hint="name it as module:function, importable from the current directory",
        ) from None
    return provider


@dataclass(frozen=True)
class SimulationRun:
    """What a simulated replay produced."""

    published: list[Published]
    account: Account


def simulate_with_ghdl(
    design: Design,
    bag: Path,
    topic_names: Mapping[str, str],
    top: SimulationTop,
    workdir: Path,
    *,
    queues: QueueConfig,
    screen: bool = True,
    settings: ReplaySettings = DEFAULT_SETTINGS,
    simulator: str = "ghdl",
    notice: Callable[[str], None] | None = None,
) -> SimulationRun:
    """Replay `bag` through the design's logic in GHDL (or Verilator) with the runtime in cocotb.

    Args:
        design: The holistic model (its spec file is compiled again in the simulator).
        bag: The input bag.
        topic_names: Bag topic → the spec's topic, for every topic to replay.
        top: The logic's top-level (from a `TopProvider`).
        workdir: Scratch folder (VHDL, simulation build, results).
        queues: The processor's callback queues.
        screen: Whether the processor refuses malformed messages itself (else the logic's
            subscribers drop them; the account reads their counts, ``logic:<reason>``).
        settings: The replay settings.
        simulator: ``ghdl`` (the VHDL) or ``verilator`` (the top's ``verilog`` files).
        notice: Told in one line which GHDL back-end runs the logic, and whether it compiles
            the logic or reuses what an earlier run compiled.

    Raises:
        CosimError: The simulation failed (a bug in rfc or in the logic).
        StallError: The logic stalled.
    """
    job: CosimJob = {
        "spec": str(design.project.spec_file),
        "bag": str(bag),
        "topics": sorted(topic_names),
        "topic_names": dict(topic_names),
        "clock_mhz": design.project.clock_mhz,
        "policy": queues.policy.value,
        "depth": queues.depth,
        "screen": screen,
        "drain_cycles": settings.drain_cycles,
        "stall_cycles": settings.stall_cycles,
        "seed": settings.seed,
        "results": str(workdir / "published.rec"),
        "account": str(workdir / "account.json"),
        "progress": str(workdir / "progress"),
        "stalled": str(workdir / "stalled.json"),
        "busy": list(getattr(top, "busy", ())),
        "warnings": str(workdir / "warnings.json"),
    }
    job_file = workdir / "job.json"
    job_file.write_text(json.dumps(job, indent=1))
    compiled = ghdl_program(top, notice or (lambda line: None)) if simulator == "ghdl" else None
    failure: list[BaseException] = []

    def simulate() -> None:
        try:
            run_cocotb(
                getattr(top, "verilog", ()) if simulator == "verilator" else top.sources,
                top.top,
                "rfc.sim.cosim",
                workdir / "sim",
                env={"RFC_SIM_JOB": str(job_file)},
                seed=settings.seed,
                simulator=simulator,
                compiled=compiled,
            )
        except BaseException as exc:  # handed to the caller's thread below
            failure.append(exc)

    worker = threading.Thread(target=simulate, name="rfc-ghdl")
    worker.start()
    while worker.is_alive():
        worker.join(0.25)
        if settings.progress is not None and (text := _read(workdir / "progress")):
            settings.progress(int(text))
    if failure:
        raise failure[0]
    if stalled := _read(Path(job["stalled"])):
        report = json.loads(stalled)
        raise StallError(report["message"], hint=report["hint"])
    if not Path(job["account"]).is_file():
        raise CosimError(f"the simulation wrote no account (see {workdir / 'sim'})")
    if settings.warnings is not None:
        settings.warnings.extend(json.loads(Path(job["warnings"]).read_text()))
    return SimulationRun(
        list(read_records(Path(job["results"]))),
        Account.from_json(json.loads(Path(job["account"]).read_text())),
    )


def ghdl_program(top: SimulationTop, notice: Callable[[str], None]) -> CompiledLogic | None:
    """The logic compiled by GHDL's fastest installed back-end, once per content of its VHDL.

    None when only mcode is installed: it compiles the logic in memory at every run.

    Raises:
        CosimError: GHDL cannot compile the logic.
    """
    backend = fastest_backend()
    if not backend.compiles:
        why = (
            "GHDL_BACKEND chose it"
            if os.environ.get("GHDL_BACKEND") == backend.name
            else "tools/setup.sh installs the faster llvm one"
        )
        notice(f"GHDL's {backend.name} back-end runs the logic (compiled at every run; {why})")
        return None
    logic = compiled_logic(top.sources, top.top, backend)
    if logic.compiled:
        notice(f"GHDL's {backend.name} back-end runs the logic compiled before ({logic.folder})")
    else:
        notice(f"GHDL's {backend.name} back-end compiles the logic, once ({logic.folder})")
    compile_logic(logic, top.sources)
    return logic


def _read(path: Path) -> str:
    try:
        return path.read_text().strip()
    except OSError:
        return ""
