"""Random traffic traces recorded from a model, replayed on the hardware (MyHDL and GHDL).

A trace is driven closed-loop by the model (publishers hold `tvalid` until their last beat,
with random gaps and a randomly stalling channel) and records, per cycle, the inputs and the
model's grant. Replaying the inputs on the hardware and comparing its grant cycle by cycle is
equivalent to running the hardware closed-loop up to the first difference, which is reported.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rfc.lib.schedulers.model import model_of
from rfc.lib.schedulers.model.traffic import Publishers
from rfc.lib.schedulers.spec import AnySchedulerSpec


@dataclass(frozen=True)
class Trace:
    """Per-cycle channel signals: request/last bool[C, N], ready bool[C], grant int[C]."""

    request: np.ndarray
    last: np.ndarray
    ready: np.ndarray
    grant: np.ndarray

    @property
    def cycles(self) -> int:
        return len(self.grant)

    def save(self, path: Path) -> None:
        path.write_text(
            json.dumps(
                {
                    "request": [bits_to_int(row) for row in self.request],
                    "last": [bits_to_int(row) for row in self.last],
                    "ready": self.ready.astype(int).tolist(),
                    "grant": self.grant.tolist(),
                }
            )
        )


def bits_to_int(row: np.ndarray) -> int:
    return int(sum(1 << int(i) for i in np.nonzero(row)[0]))


def one_hot_index(value: int) -> int:
    """-1 for 0, the bit index for a one-hot value; raises for more than one bit."""
    if value == 0:
        return -1
    if value & (value - 1):
        raise AssertionError(f"grant {value:#x} has more than one bit set")
    return value.bit_length() - 1


def record_trace(
    spec: AnySchedulerSpec, cycles: int, seed: int, stall: float = 0.1, max_gap: int | None = None
) -> Trace:
    """Run `spec`'s model closed-loop on random traffic for `cycles` cycles."""
    rng = np.random.default_rng(seed)
    model = model_of(spec, batch=1)
    gap = max_gap if max_gap is not None else 2 * spec.n + 4
    publishers = Publishers(np.asarray([spec.transfer]), max_gap=gap, rng=rng)
    rows = {"request": [], "last": [], "ready": [], "grant": []}
    for _ in range(cycles):
        request, last = publishers.request, publishers.last
        ready = rng.random(1) >= stall
        grant = model.step(request, last, ready)
        publishers.advance(grant)
        rows["request"].append(request[0])
        rows["last"].append(last[0])
        rows["ready"].append(ready[0])
        rows["grant"].append(int(grant[0]))
    return Trace(*(np.asarray(rows[k]) for k in ("request", "last", "ready", "grant")))


def first_difference(expected: np.ndarray, actual: np.ndarray, trace: Trace) -> str | None:
    """None when the grants agree on every cycle, else a description of the first difference."""
    differ = np.nonzero(np.asarray(expected) != np.asarray(actual))[0]
    if differ.size == 0:
        return None
    k = int(differ[0])
    return (
        f"cycle {k}: model grants {expected[k]}, hardware {actual[k]} "
        f"(request {bits_to_int(trace.request[k]):#x}, last {bits_to_int(trace.last[k]):#x}, "
        f"ready {int(trace.ready[k])})"
    )
