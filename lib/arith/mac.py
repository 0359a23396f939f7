"""Bit-exact models of the fixed-point multiply and multiply-accumulate blocks.

Operands and results share one `FixedFormat`. Products are kept whole (twice the fraction bits)
and summed exactly; only the final result is rounded, to nearest with ties up
(``floor(x + 1/2)``), then saturated to the format. The functions accept Python ints or NumPy
object arrays of them (exact big integers, vectorised).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from rfc.lib.fixed import FixedFormat

#: Extra accumulator bits above a product's: sums of up to 2**4 products never wrap.
MAC_GUARD_BITS = 4


def round_product(total: Any, fmt: FixedFormat) -> Any:
    """A sum of products (``2 * frac_bits`` fraction bits) rounded half up and saturated."""
    half = (1 << fmt.frac_bits) >> 1
    rounded = (total + half) >> fmt.frac_bits
    if isinstance(rounded, np.ndarray):
        return np.clip(rounded, fmt.min_raw, fmt.max_raw)
    return min(max(rounded, fmt.min_raw), fmt.max_raw)


def multiply(a: Any, b: Any, fmt: FixedFormat) -> Any:
    """``a * b`` of raw integers of `fmt`, rounded half up and saturated to `fmt`."""
    return round_product(a * b, fmt)


def multiply_accumulate(pairs: Iterable[tuple[Any, Any]], fmt: FixedFormat) -> Any:
    """``Σ a * b`` over `pairs` (at most ``2**MAC_GUARD_BITS``), rounded once at the end.

    Raises:
        ValueError: More pairs than the accumulator's guard bits allow.
    """
    pairs = list(pairs)
    if not 1 <= len(pairs) <= 1 << MAC_GUARD_BITS:
        raise ValueError(f"a sum takes 1 to {1 << MAC_GUARD_BITS} products, not {len(pairs)}")
    return round_product(sum(a * b for a, b in pairs), fmt)
