"""Random traffic traces recorded from a model, replayed on the hardware (MyHDL and GHDL).

A trace is driven closed-loop by the model (publishers hold `tvalid` until their last beat,
with random gaps and a randomly stalling channel) and records, per cycle, the inputs and the
model's grant. Replaying the inputs on the hardware and comparing its grant cycle by cycle is
equivalent to running the hardware closed-loop up to the first difference, which is reported.
"""

from __future__ import annotations

import numpy as np

from rfc.dse.trace import Trace, bits_to_int, record
from rfc.lib.schedulers.model import model_of
from rfc.lib.schedulers.model.traffic import Publishers
from rfc.lib.schedulers.spec import Algorithm, AnySchedulerSpec, CompositionSpec, SchedulerSpec


def record_trace(
    spec: AnySchedulerSpec, cycles: int, seed: int, stall: float = 0.1, max_gap: int | None = None
) -> Trace:
    """Run `spec`'s model closed-loop on random traffic for `cycles` cycles."""
    rng = np.random.default_rng(seed)
    gap = max_gap if max_gap is not None else 2 * spec.n + 4
    publishers = Publishers(np.asarray([spec.transfer]), max_gap=gap, rng=rng)
    return record(model_of(spec), publishers, cycles, ready=lambda: rng.random() >= stall)


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
