"""The number format shared by the fixed-point blocks: signed two's complement, binary point."""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from myhdl import Signal, intbv


@dataclass(frozen=True)
class FixedFormat:
    """Signed two's-complement fixed point: `width` bits, `frac_bits` of them after the point.

    The raw integer ``r`` stands for the value ``r / 2**frac_bits``; the representable values run
    from ``-2**(width - 1)`` to ``2**(width - 1) - 1`` raw, so ``width - frac_bits`` integer bits
    include the sign (``FixedFormat(54, 52)`` covers [-2, 2) in steps of 2**-52).

    Attributes:
        width: Total bits, sign included (at least 2).
        frac_bits: Bits after the binary point (0 or more, fewer than 1023 so that every value
            is a normal float64).
    """

    width: int
    frac_bits: int

    def __post_init__(self) -> None:
        if self.width < 2:
            raise ValueError(f"a signed fixed-point format needs at least 2 bits, not {self.width}")
        if not 0 <= self.frac_bits <= 1022:
            raise ValueError(f"frac_bits must lie in 0..1022, not {self.frac_bits}")
        if self.width - self.frac_bits > 1023:
            raise ValueError(
                f"{self.width - self.frac_bits} integer bits exceed float64's exponent range"
            )

    @property
    def int_bits(self) -> int:
        """Bits before the point, the sign included."""
        return self.width - self.frac_bits

    @property
    def min_raw(self) -> int:
        """The most negative raw integer."""
        return -(1 << (self.width - 1))

    @property
    def max_raw(self) -> int:
        """The most positive raw integer."""
        return (1 << (self.width - 1)) - 1

    def value(self, raw: int) -> Fraction:
        """The exact number a raw integer stands for."""
        return Fraction(raw, 1 << self.frac_bits)

    def signal(self, raw: int = 0) -> Signal:
        """A MyHDL signal holding raw integers of this format."""
        return Signal(intbv(raw, min=self.min_raw, max=self.max_raw + 1))
