"""`rfc dse --verify-hdl`: sampled points re-run on the generated schedulers in GHDL.

For each algorithm, replicate 0 of the main dataset at the smallest N: the scheduler is
generated with that replicate's T and D and the counter width the DSE used, the model records
the run closed-loop (the same traffic as the kernel), GHDL replays it through cocotb, and the
metrics measured on the hardware's own grants (`rfc.dse.channel.measure`) must equal, value
for value, the ones the DSE reported for that replicate.
"""

from __future__ import annotations

import json
import math
import tempfile
import warnings
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from rfc.dse.channel import measure
from rfc.dse.datasets import dataset, draw
from rfc.dse.kernel import METRICS
from rfc.dse.plots import main_dataset
from rfc.dse.sweep import ALGORITHMS, SweepResult
from rfc.dse.trace import Trace, record
from rfc.lib.schedulers.model import model_of
from rfc.lib.schedulers.model.traffic import Publishers
from rfc.lib.schedulers.spec import AnySchedulerSpec, SchedulerSpec
from rfc.toolchain import CosimError, run_cocotb

#: The cocotb module that replays a trace.
REPLAY = "rfc.dse.hdl_replay"


def replay_in_ghdl(
    spec: AnySchedulerSpec, trace: Trace, directory: Path
) -> npt.NDArray[np.int64] | None:
    """Replay `trace` on the generated `spec` in GHDL; the hardware's grant on every cycle.

    Returns:
        The grants up to the first difference (all of them when equal), or None when the
        simulation produced none.

    Raises:
        CosimError: The hardware's grant differs from the trace's (the message names the
            cycle), or the simulation failed.
    """
    from rfc.lib.schedulers.generate import generate_hdl

    files = generate_hdl(spec, directory / "hdl", "dut")
    trace.save(directory / "trace.json")
    grants_path = directory / "grants.json"
    env = {"SCHED_TRACE": str(directory / "trace.json"), "SCHED_GRANTS": str(grants_path)}
    try:
        run_cocotb(files, "dut", REPLAY, directory / "sim", env=env)
    finally:
        grants = np.asarray(json.loads(grants_path.read_text())) if grants_path.exists() else None
    return grants


@dataclass(frozen=True)
class Check:
    """One verified point: the DSE's metrics and the hardware's.

    Attributes:
        scheduler: The algorithm.
        dataset: Dataset name.
        n: Accelerators.
        cycles: Cycles simulated.
        expected: The DSE kernel's metrics of replicate 0.
        measured: The metrics of the GHDL run (None when it failed).
        error: Why the GHDL run failed, if it did.
    """

    scheduler: str
    dataset: str
    n: int
    cycles: int
    expected: tuple[float, ...]
    measured: tuple[float, ...] | None
    error: str | None = None

    @property
    def equal(self) -> bool:
        """Every metric equal (NaN equal to NaN)."""
        if self.measured is None:
            return False
        return all(
            (math.isnan(a) and math.isnan(b)) or a == b
            for a, b in zip(self.expected, self.measured, strict=True)
        )

    def as_dict(self) -> dict[str, object]:
        """JSON-friendly form."""

        def values(row: tuple[float, ...] | None) -> dict[str, float | None] | None:
            if row is None:
                return None
            return {m: None if math.isnan(v) else v for m, v in zip(METRICS, row, strict=True)}

        return {
            "scheduler": self.scheduler,
            "dataset": self.dataset,
            "n": self.n,
            "cycles": self.cycles,
            "equal": self.equal,
            "dse": values(self.expected),
            "ghdl": values(self.measured),
            "error": self.error,
        }


def _check(result: SweepResult, algorithm: str, name: str, n: int, scratch: Path) -> Check:
    point = result.point(name, algorithm, n)
    assert point is not None
    traffic = draw(dataset(name), n, 1, result.plan.seed)
    spec = SchedulerSpec.create(
        algorithm,
        n,
        traffic.transfer[0].tolist(),
        traffic.deadline[0].tolist(),
        counter_bits=point.counter_bits,
    )
    trace = record(model_of(spec), Publishers(traffic.transfer, gap=traffic.idle), point.cycles)
    expected = tuple(float(v) for v in point.rows[0])
    try:
        grants = replay_in_ghdl(spec, trace, scratch)
    except CosimError as error:
        return Check(algorithm, name, n, point.cycles, expected, None, str(error))
    if grants is None:
        return Check(algorithm, name, n, point.cycles, expected, None, "GHDL recorded no grant")
    measured = measure(trace.request, trace.last, grants, traffic.deadline[0])
    return Check(algorithm, name, n, point.cycles, expected, tuple(float(v) for v in measured))


def verify_hdl(result: SweepResult, jobs: int) -> list[Check]:
    """Re-run each algorithm's first replicate at the smallest N of the main dataset in GHDL."""
    name, n = main_dataset(result), min(result.plan.sizes)
    # MyHDL warns about unread padding signals; generate_hdl silences them, but its
    # catch_warnings is not thread-safe, so silence them for all the threads here.
    with warnings.catch_warnings(), tempfile.TemporaryDirectory(prefix="rfc-dse-") as scratch:
        warnings.simplefilter("ignore")
        folders = [Path(scratch) / algorithm for algorithm in ALGORITHMS]
        with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
            return list(
                pool.map(
                    lambda pair: _check(result, pair[0], name, n, pair[1]),
                    zip(ALGORITHMS, folders, strict=True),
                )
            )
