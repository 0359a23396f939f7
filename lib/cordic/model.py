"""Bit-exact model of the vectoring CORDIC: the same integer steps as the hardware."""

from __future__ import annotations

from dataclasses import dataclass

from rfc.lib.cordic.config import CordicConfig


@dataclass(frozen=True)
class Vectored:
    """What a vectoring CORDIC returns for (x, y).

    Attributes:
        angle: atan2(y, x) in radians as a raw integer with `angle_frac` fraction bits, in
            [-π, π] up to the residual of the iterations; exact for y = 0 (0 for (0, 0)).
        magnitude: gain · sqrt(x² + y²) in the inputs' scale, rounded down.
    """

    angle: int
    magnitude: int


def vectoring(x: int, y: int, config: CordicConfig) -> Vectored:
    """Rotate (x, y) onto the positive x axis, summing the angles turned through.

    Inputs with negative x are first turned by π (negated) and the angle starts at ±π (+π when
    y >= 0), so the micro-rotations only ever cover [-π/2, π/2]. Each iteration i turns by
    ±atan(2**-i), towards y = 0; shifts are arithmetic (rounding down), as in the hardware.
    When y is 0 the angle is exact (0, or π for negative x; 0 for (0, 0)): the iterations still
    run for the magnitude, but their angles are not summed, so that level vectors give exactly
    0 rather than the residual of the iterations.

    Raises:
        ValueError: x or y does not fit in `config.width` signed bits.
    """
    low, high = -(1 << (config.width - 1)), (1 << (config.width - 1)) - 1
    if not (low <= x <= high and low <= y <= high):
        raise ValueError(f"({x}, {y}) does not fit in {config.width} signed bits")
    angle = 0
    level = y == 0
    if x < 0:
        angle = config.pi if y >= 0 else -config.pi
        x, y = -x, -y
    x <<= config.guard
    y <<= config.guard
    for i, step in enumerate(config.atan_table):
        turn = 0 if level else step
        if y >= 0:
            x, y, angle = x + (y >> i), y - (x >> i), angle + turn
        else:
            x, y, angle = x - (y >> i), y + (x >> i), angle - turn
    return Vectored(angle, x >> config.guard)
