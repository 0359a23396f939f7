"""Sine and cosine by rotation-mode CORDIC: configuration and bit-exact model.

The model works on NumPy int64 arrays (every register of a valid configuration fits in 63
bits), so it checks hundreds of thousands of angles at once and still makes the same integer
steps as the hardware in `rfc.lib.arith.sincos_hdl`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rfc.lib.cordic.config import arctan_table, default_guard, gain_squared, quarter_pi
from rfc.lib.fixed import FixedFormat

#: Extra bits carried while computing the inverse gain, removed by its final rounding.
_ROOT_GUARD = 16
#: Widest internal register the int64 model can hold (one bit of headroom for the sums).
_MODEL_BITS = 62


def inverse_gain(iterations: int, frac_bits: int) -> int:
    """``round(2**frac_bits / ∏ sqrt(1 + 2**-2i))``: the start that makes the result unscaled."""
    numerator, shift = gain_squared(iterations)
    squared = (1 << (2 * (frac_bits + _ROOT_GUARD) + shift)) // numerator
    return (math.isqrt(squared) + (1 << (_ROOT_GUARD - 1))) >> _ROOT_GUARD


# Beside CordicConfig, not one with it: rotation mode has no input width, starts from the
# inverse gain and reduces its angle, so its registers' widths follow other rules.
@dataclass(frozen=True)
class SinCosConfig:
    """The shape of a sine/cosine CORDIC.

    Attributes:
        frac_bits: Fraction bits of the angle (radians) and of the results.
        iterations: Micro-rotations; None picks ``frac_bits + 2``, which leaves an angle
            residual below half a unit of the results.
        guard_bits: Extra low bits carried through the iterations against rounding drift;
            None picks ``ceil(log2(iterations)) + 2``.
    """

    frac_bits: int
    iterations: int | None = None
    guard_bits: int | None = None

    def __post_init__(self) -> None:
        if self.frac_bits < 2:
            raise ValueError(f"sine/cosine needs at least 2 fraction bits, not {self.frac_bits}")
        if self.iterations is not None and self.iterations < 1:
            raise ValueError(f"a CORDIC needs at least one iteration, not {self.iterations}")
        if self.guard_bits is not None and self.guard_bits < 1:
            raise ValueError(f"guard_bits must be at least 1, not {self.guard_bits}")
        if self.z_width + 2 > _MODEL_BITS:
            raise ValueError(
                f"frac_bits {self.frac_bits} with {self.guard} guard bits needs registers wider "
                f"than {_MODEL_BITS} bits; use at most {_MODEL_BITS - 5 - self.guard}"
            )

    @property
    def steps(self) -> int:
        """Micro-rotations in use."""
        return self.iterations if self.iterations is not None else self.frac_bits + 2

    @property
    def guard(self) -> int:
        """Guard bits in use."""
        return self.guard_bits if self.guard_bits is not None else default_guard(self.steps)

    @property
    def precision(self) -> int:
        """Fraction bits of the internal registers."""
        return self.frac_bits + self.guard

    @property
    def angle_format(self) -> FixedFormat:
        """The angle input: radians in [-8, 8), reduced modulo 2π inside."""
        return FixedFormat(self.frac_bits + 4, self.frac_bits)

    @property
    def out_format(self) -> FixedFormat:
        """The cosine and sine outputs, in [-1, 1]."""
        return FixedFormat(self.frac_bits + 2, self.frac_bits)

    @property
    def xy_width(self) -> int:
        """Bits of the x/y registers (|x|, |y| <= 1 throughout, guard bits below)."""
        return self.precision + 2

    @property
    def z_width(self) -> int:
        """Bits of the residual-angle register (|z| < π/2 + π/4 < 4 throughout)."""
        return self.precision + 3

    @property
    def latency(self) -> int:
        """Cycles from the input handshake to valid output of the pipelined block."""
        return self.steps

    @property
    def iterative_latency(self) -> int:
        """The same for the iterative block, which reduces the angle over two cycles."""
        return self.steps + 1

    @cached_property
    def atan_table(self) -> tuple[int, ...]:
        """``round(atan(2**-i) * 2**precision)`` for each iteration ``i``."""
        return arctan_table(self.steps, self.precision)

    @cached_property
    def half_pi(self) -> int:
        """``round(π/2 * 2**precision)``."""
        return quarter_pi(self.precision + 1)

    @cached_property
    def pi(self) -> int:
        """``round(π * 2**precision)``."""
        return quarter_pi(self.precision + 2)

    @cached_property
    def two_pi(self) -> int:
        """``round(2π * 2**precision)``."""
        return quarter_pi(self.precision + 3)

    @cached_property
    def start(self) -> int:
        """The x register's start: the inverse CORDIC gain at `precision` fraction bits."""
        return inverse_gain(self.steps, self.precision)


def sincos(angle: np.ndarray | int, config: SinCosConfig) -> tuple[np.ndarray, np.ndarray]:
    """Cosine and sine of raw angles of `config.angle_format`, as raw `config.out_format`.

    The angle is reduced to [-π, π] by one add or subtract of 2π (enough for [-8, 8)), then to
    [-π/2, π/2] by one of π (the result is negated then). The vector (1/gain, 0) is turned
    towards the angle by ±atan(2**-i) per iteration i; shifts round down, as in the hardware.
    The outputs are rounded half up from the guard bits.

    Raises:
        ValueError: An angle does not fit in `config.angle_format`.
    """
    raw = np.asarray(angle, dtype=np.int64)
    fmt = config.angle_format
    if raw.size and (raw.min() < fmt.min_raw or raw.max() > fmt.max_raw):
        raise ValueError(f"angles must be raw integers of {fmt}")
    z = raw << config.guard
    z = np.where(z > config.pi, z - config.two_pi, np.where(z < -config.pi, z + config.two_pi, z))
    flip = (z > config.half_pi) | (z < -config.half_pi)
    z = np.where(z > config.half_pi, z - config.pi, np.where(z < -config.half_pi, z + config.pi, z))
    x = np.full_like(z, config.start)
    y = np.zeros_like(z)
    for i, step in enumerate(config.atan_table):
        down = z < 0
        dx, dy = y >> i, x >> i
        x, y = np.where(down, x + dx, x - dx), np.where(down, y - dy, y + dy)
        z = np.where(down, z + step, z - step)
    half = 1 << (config.guard - 1)
    cos = (np.where(flip, -x, x) + half) >> config.guard
    sin = (np.where(flip, -y, y) + half) >> config.guard
    return cos, sin
