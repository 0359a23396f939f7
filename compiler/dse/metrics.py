"""Summaries over replicates: the mean and its 95 % confidence interval (Student's t).

A replicate whose metric is undefined (NaN: no completed message, say) is left out of that
metric's summary; `count` says how many replicates it rests on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

#: Two-sided 95 % quantiles of Student's t for 1 … 30 degrees of freedom.
_T95 = (
    12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
    2.201, 2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
    2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042,
)  # fmt: skip
_Z95 = 1.959964


def t_quantile_95(freedom: int) -> float:
    """The 97.5 % quantile of Student's t with `freedom` degrees of freedom.

    Tabulated up to 30; beyond, the Cornish-Fisher expansion around the normal quantile
    (error below 1e-4).
    """
    if freedom < 1:
        raise ValueError("a confidence interval needs at least two replicates")
    if freedom <= len(_T95):
        return _T95[freedom - 1]
    z = _Z95
    return (
        z
        + (z**3 + z) / (4 * freedom)
        + (5 * z**5 + 16 * z**3 + 3 * z) / (96 * freedom**2)
        + (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / (384 * freedom**3)
    )


# Fields and values derived from them, like the loopback's FrameTiming in shape only: statistics.
@dataclass(frozen=True)
class Summary:
    """Mean of a metric over replicates with the half-width of its 95 % confidence interval.

    Attributes:
        mean: Mean over the replicates where the metric is defined (NaN if none).
        ci95: Half-width of the 95 % interval (0 for one replicate, NaN for none).
        count: Replicates it rests on.
    """

    mean: float
    ci95: float
    count: int

    @property
    def low(self) -> float:
        """Lower bound of the interval."""
        return self.mean - self.ci95

    @property
    def high(self) -> float:
        """Upper bound of the interval."""
        return self.mean + self.ci95

    def as_dict(self) -> dict[str, float | int | None]:
        """JSON-friendly form (NaN becomes None)."""
        return {
            "mean": _finite(self.mean),
            "ci95": _finite(self.ci95),
            "low": _finite(self.low),
            "high": _finite(self.high),
            "replicates": self.count,
        }


def _finite(value: float) -> float | None:
    return None if math.isnan(value) else round(float(value), 6)


def summarize(values: npt.ArrayLike) -> Summary:
    """Mean and 95 % confidence half-width of `values` (NaNs left out)."""
    data = np.asarray(values, dtype=np.float64)
    data = data[~np.isnan(data)]
    if data.size == 0:
        return Summary(math.nan, math.nan, 0)
    if data.size == 1:
        return Summary(float(data[0]), 0.0, 1)
    spread = float(np.std(data, ddof=1)) / math.sqrt(data.size)
    return Summary(float(data.mean()), t_quantile_95(data.size - 1) * spread, int(data.size))
