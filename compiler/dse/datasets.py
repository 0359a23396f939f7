"""The traffic of the paper's evaluation (§7.2, docs/dse.md): datasets, seeded and reproducible.

Accelerator i has a transfer time T_i (beats, one per cycle) and an idle time F_i after its last
beat before its next message is ready; all are released at cycle 0 and the implicit deadline is
D_i = T_i + F_i after arrival. T and F are drawn from normal distributions, rounded and clipped
to at least 1. Replicate r of a dataset at N inputs is drawn from its own random stream
(seed, dataset, N, r), so the first R replicates are the same whatever R is, and every
scheduler sees the same traffic.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rfc.errors import RfcError, did_you_mean
from rfc.lib.schedulers.model.tree import IntArray, Replicated

#: Numbers of accelerators the paper evaluates.
SIZES = (2, 4, 8, 16, 32, 64, 128, 256)
#: Clock of every simulation (paper: 100 MHz).
CLOCK_MHZ = 100


@dataclass(frozen=True)
class Dataset:
    """One exploration space of the paper.

    Attributes:
        name: ``large`` or ``cc1`` … ``cc4``.
        transfer_mean: Mean of T (beats).
        idle_mean: Mean of F (cycles).
        sigma: Standard deviation of both.
        duration_us: Simulated time per replicate.
        replicates: Replicates the paper draws.
    """

    name: str
    transfer_mean: float
    idle_mean: float
    sigma: float
    duration_us: float
    replicates: int

    @property
    def cycles(self) -> int:
        """Simulated cycles per replicate at `CLOCK_MHZ`."""
        return round(self.duration_us * CLOCK_MHZ)

    @property
    def label(self) -> str:
        """A caption, such as ``cc2: T ~ N(20, 10), F ~ N(180, 10)``."""
        return (
            f"{self.name}: T ~ N({self.transfer_mean:g}, {self.sigma:g}), "
            f"F ~ N({self.idle_mean:g}, {self.sigma:g})"
        )


DATASETS = {
    d.name: d
    for d in (
        Dataset("large", 100, 100, 50, 100, 200),
        Dataset("cc1", 20, 20, 10, 500, 10),
        Dataset("cc2", 20, 180, 10, 500, 10),
        Dataset("cc3", 180, 20, 10, 500, 10),
        Dataset("cc4", 180, 180, 10, 500, 10),
    )
}


def dataset(name: str) -> Dataset:
    """The dataset called `name`.

    Raises:
        RfcError: No such dataset; the closest name is suggested.
    """
    try:
        return DATASETS[name.strip().lower()]
    except KeyError:
        names = list(DATASETS)
        raise RfcError(
            f"unknown dataset '{name}'; expected one of {', '.join(names)}",
            hint=did_you_mean(name, names),
        ) from None


@dataclass(frozen=True)
class Traffic(Replicated):
    """Timing of N publishers on R replicates: int[R, N] each.

    Attributes:
        transfer: T_i, beats per message.
        idle: F_i, idle cycles after a message's last beat.
        deadline: D_i, relative deadline (implicit: T_i + F_i).
    """

    transfer: IntArray
    idle: IntArray
    deadline: IntArray


def draw(data: Dataset, n: int, replicates: int, seed: int = 0) -> Traffic:
    """Replicates 0 … R-1 of `data` with `n` accelerators (implicit deadlines)."""
    index = list(DATASETS).index(data.name)
    transfer = np.empty((replicates, n), dtype=np.int64)
    idle = np.empty((replicates, n), dtype=np.int64)
    for r in range(replicates):
        rng = np.random.default_rng([seed, index, n, r])
        transfer[r] = np.clip(np.rint(rng.normal(data.transfer_mean, data.sigma, n)), 1, None)
        idle[r] = np.clip(np.rint(rng.normal(data.idle_mean, data.sigma, n)), 1, None)
    return Traffic(transfer, idle, transfer + idle)
