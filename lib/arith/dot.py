"""Bit-exact model of the fixed-point dot-product block (`rfc.lib.arith.dot_hdl`).

Operands and result share one `FixedFormat`. The N products are kept whole (twice the fraction
bits) and summed exactly; only the sum is rounded, half up, then saturated, as
`rfc.lib.arith.mac.round_product` does. Works on Python ints or NumPy object arrays of them
(exact big integers, vectorised over many dot products at once).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rfc.lib.arith.mac import round_product
from rfc.lib.fixed import FixedFormat


def dot_product(a: Sequence[Any], b: Sequence[Any], fmt: FixedFormat) -> Any:
    """``Σ a[i] * b[i]`` of raw integers of `fmt`, rounded once, half up, and saturated.

    Raises:
        ValueError: No terms, or `a` and `b` of different lengths.
    """
    if not a or len(a) != len(b):
        raise ValueError(
            f"a dot product takes two equal, non-empty lists, not {len(a)} and {len(b)}"
        )
    return round_product(sum(x * y for x, y in zip(a, b, strict=True)), fmt)


def dot_sum_levels(terms: int) -> int:
    """Registered adder levels that sum `terms` products (a lone product still gets one)."""
    return max(1, (terms - 1).bit_length())


def dot_latency(terms: int) -> int:
    """Cycles from the input handshake to `out_valid` for `terms` products.

    Operand registers, product registers, the adder levels and the rounding register; the
    first of them takes the input, so the latency is one fewer than the registers.
    """
    return 2 + dot_sum_levels(terms)
