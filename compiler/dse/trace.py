"""Channel traces: per-cycle scheduler inputs and grants, recorded from a model and replayed.

A trace is driven closed-loop by a model (publishers hold `tvalid` until their last beat) and
records, per cycle, `request`, `last`, `ready` and the model's grant. Replaying its inputs on
the hardware and comparing the grant cycle by cycle is equivalent to running the hardware
closed-loop up to the first difference. `--verify-hdl` and the co-simulation tests share it.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from rfc.lib.schedulers.model import SchedulerModel
from rfc.lib.schedulers.model.traffic import Publishers


@dataclass(frozen=True)
class Trace:
    """Per-cycle channel signals: request/last bool[C, N], ready bool[C], grant int[C]."""

    request: npt.NDArray[np.bool_]
    last: npt.NDArray[np.bool_]
    ready: npt.NDArray[np.bool_]
    grant: npt.NDArray[np.int64]

    @property
    def cycles(self) -> int:
        """C."""
        return len(self.grant)

    def save(self, path: Path) -> None:
        """Write the JSON form `rfc.dse.hdl_replay` reads (bit vectors as integers)."""
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


def bits_to_int(row: npt.NDArray[np.bool_]) -> int:
    """The bit vector as an integer, input 0 in bit 0."""
    return int(sum(1 << int(i) for i in np.nonzero(row)[0]))


def one_hot_index(value: int) -> int:
    """-1 for 0, the bit index for a one-hot value.

    Raises:
        AssertionError: More than one bit is set (a broken grant).
    """
    if value == 0:
        return -1
    if value & (value - 1):
        raise AssertionError(f"grant {value:#x} has more than one bit set")
    return value.bit_length() - 1


def record(
    model: SchedulerModel,
    publishers: Publishers,
    cycles: int,
    ready: Callable[[], bool] | None = None,
) -> Trace:
    """Run a batch-1 `model` closed-loop on `publishers` for `cycles` cycles.

    Args:
        model: The scheduler (one replicate).
        publishers: Its traffic (one replicate).
        cycles: Cycles to record.
        ready: Draws the channel's `ready` each cycle (None: always ready).
    """
    rows: dict[str, list[int]] = {"request": [], "last": [], "ready": [], "grant": []}
    for _ in range(cycles):
        request, last = publishers.request, publishers.last
        accepts = np.array([True if ready is None else ready()])
        grant = model.step(request, last, accepts)
        publishers.advance(grant)
        rows["request"].append(request[0])
        rows["last"].append(last[0])
        rows["ready"].append(accepts[0])
        rows["grant"].append(int(grant[0]))
    return Trace(*(np.asarray(rows[k]) for k in ("request", "last", "ready", "grant")))
