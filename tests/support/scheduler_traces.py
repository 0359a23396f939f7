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
from rfc.lib.schedulers.spec import Algorithm, AnySchedulerSpec, CompositionSpec, SchedulerSpec


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


#: What the equivalence tests co-simulate: the six algorithms and one composition.
COMPOSITION = "LRU(LOEDF,LST)"
DESIGNS = (*(a.value for a in Algorithm), COMPOSITION)
#: Input counts of the equivalence tests (issue 5).
COSIM_INPUTS = (2, 3, 8, 33)
#: At this input count the timed algorithms get the narrowest legal counters, so that the
#: traces drive them into saturation (LOEDF, LST) and wrap-around (ROEDF).
NARROW_AT = 8


def cosim_spec(design: str, n: int) -> AnySchedulerSpec:
    """The spec co-simulated for `design` with `n` inputs: random T in 1..10, D = T + 1..30."""
    rng = np.random.default_rng(n)
    transfer = rng.integers(1, 11, size=n).tolist()
    deadline = [t + int(d) for t, d in zip(transfer, rng.integers(1, 31, size=n), strict=True)]
    bits = None
    if n == NARROW_AT:
        bits = max(t + d for t, d in zip(transfer, deadline, strict=True)).bit_length() + 1
    if design == COMPOSITION:
        half = n // 2
        return CompositionSpec.create(
            "LRU",
            [
                SchedulerSpec.create("LOEDF", half, transfer[:half], deadline[:half], bits),
                SchedulerSpec.create("LST", n - half, transfer[half:], deadline[half:], bits),
            ],
        )
    return SchedulerSpec.create(design, n, transfer, deadline, bits)


def checked_rule(design: str, n: int) -> Algorithm | None:
    """The algorithm whose rule the properties hold a trace to (None: generic checks only).

    Narrow counters saturate or wrap by design, which the paper's rules do not model, and a
    composition follows no single algorithm's rule.
    """
    if design == COMPOSITION:
        return None
    algorithm = Algorithm(design)
    if algorithm.timed and n == NARROW_AT:
        return None
    return algorithm
