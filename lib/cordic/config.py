"""A CORDIC's parameters and the exact constants derived from them.

The constants (arctangent table, π, the gain) are computed with integer arithmetic to any
precision, not from `math`, whose doubles would limit the angle to 53 bits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

#: Extra bits carried while summing a series, removed by the final rounding.
_SERIES_GUARD = 16


def arctan_of_inverse(n: int, frac_bits: int) -> int:
    """``round(atan(1/n) * 2**frac_bits)`` for an integer ``n >= 2``, by the Taylor series."""
    scale = 1 << (frac_bits + _SERIES_GUARD)
    power = scale // n
    total = power
    k = 1
    while power:
        power //= n * n
        term = power // (2 * k + 1)
        total += -term if k % 2 else term
        k += 1
    return (total + (1 << (_SERIES_GUARD - 1))) >> _SERIES_GUARD


def quarter_pi(frac_bits: int) -> int:
    """``round(π/4 * 2**frac_bits)`` by Machin's formula: π/4 = 4·atan(1/5) - atan(1/239)."""
    wide = frac_bits + _SERIES_GUARD
    exact = 4 * arctan_of_inverse(5, wide) - arctan_of_inverse(239, wide)
    return (exact + (1 << (_SERIES_GUARD - 1))) >> _SERIES_GUARD


def default_guard(iterations: int) -> int:
    """Guard bits against the rounding drift of `iterations` truncated shifts: log2 of them + 2."""
    return math.ceil(math.log2(iterations)) + 2 if iterations > 1 else 2


def arctan_table(iterations: int, frac_bits: int) -> tuple[int, ...]:
    """``round(atan(2**-i) * 2**frac_bits)`` for each micro-rotation ``i``."""
    rest = (arctan_of_inverse(1 << i, frac_bits) for i in range(1, iterations))
    return (quarter_pi(frac_bits), *rest)


def gain_squared(iterations: int) -> tuple[int, int]:
    """The CORDIC gain's square ``∏ (1 + 2**-2i)`` as (numerator, log2 of its denominator)."""
    numerator = math.prod((1 << (2 * i)) + 1 for i in range(iterations))
    return numerator, 2 * sum(range(iterations))


@dataclass(frozen=True)
class CordicConfig:
    """The shape of a vectoring CORDIC.

    Attributes:
        width: Bits of the signed raw inputs `x` and `y` (any common scale: the angle does not
            depend on it, the magnitude comes out in the same scale).
        iterations: Micro-rotations; the angle error left is about ``2**(1 - iterations)`` rad.
        angle_frac: Fraction bits of the angle, in radians, signed with 3 integer bits.
        guard_bits: Extra low bits carried through the iterations against rounding drift;
            None picks ``ceil(log2(iterations)) + 2``.
    """

    width: int
    iterations: int
    angle_frac: int
    guard_bits: int | None = None

    def __post_init__(self) -> None:
        if self.width < 2:
            raise ValueError(f"CORDIC inputs need at least 2 bits, not {self.width}")
        if self.iterations < 1:
            raise ValueError(f"a CORDIC needs at least one iteration, not {self.iterations}")
        if self.angle_frac < 1:
            raise ValueError(f"angle_frac must be at least 1, not {self.angle_frac}")
        if self.guard_bits is not None and self.guard_bits < 0:
            raise ValueError(f"guard_bits cannot be negative ({self.guard_bits})")

    @property
    def guard(self) -> int:
        """Guard bits in use."""
        return self.guard_bits if self.guard_bits is not None else default_guard(self.iterations)

    @property
    def internal_width(self) -> int:
        """Bits of the x/y registers: the input, 2 bits of growth (gain·√2 < 4), the guard."""
        return self.width + 2 + self.guard

    @property
    def angle_width(self) -> int:
        """Bits of the angle (|angle| stays below π + π/4 < 4 during the iterations)."""
        return self.angle_frac + 3

    @property
    def magnitude_width(self) -> int:
        """Bits of the unsigned magnitude (gain·√2·2**(width-1) < 2**(width+1))."""
        return self.width + 1

    @property
    def pipelined_latency(self) -> int:
        """Cycles from the input handshake to valid output of the pipelined block (a stage each)."""
        return self.iterations

    @property
    def iterative_latency(self) -> int:
        """Cycles from the input handshake to valid output of the iterative block.

        Each micro-rotation takes two cycles (shift, then add), so that no path runs through a
        barrel shifter and a wide adder at once.
        """
        return 2 * self.iterations

    @property
    def iterative_interval(self) -> int:
        """Cycles between inputs the iterative block takes back to back.

        Its latency, then a cycle offering the result and an idle one before the next input.
        """
        return self.iterative_latency + 2

    @cached_property
    def atan_table(self) -> tuple[int, ...]:
        """``round(atan(2**-i) * 2**angle_frac)`` for each iteration ``i``."""
        return arctan_table(self.iterations, self.angle_frac)

    @cached_property
    def pi(self) -> int:
        """``round(π * 2**angle_frac)``: the pre-rotation of inputs with negative x."""
        return quarter_pi(self.angle_frac + 2)

    def gain(self, frac_bits: int) -> int:
        """The magnitude gain ``∏ sqrt(1 + 2**-2i)`` rounded to `frac_bits` fraction bits."""
        numerator, denominator_log2 = gain_squared(self.iterations)
        extra = 2 * (frac_bits + _SERIES_GUARD)
        squared = (numerator << extra) >> denominator_log2
        root = math.isqrt(squared)
        return (root + (1 << (_SERIES_GUARD - 1))) >> _SERIES_GUARD
