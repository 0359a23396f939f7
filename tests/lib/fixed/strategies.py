"""Hypothesis strategies for fixed-point formats and the floats worth converting to them."""

from __future__ import annotations

import random

from hypothesis import strategies as st

from rfc.lib.fixed import FixedFormat


@st.composite
def formats(draw, max_width: int = 130) -> FixedFormat:
    width = draw(st.integers(2, max_width))
    frac_bits = draw(st.integers(0, min(1022, width + 60)))
    return FixedFormat(width, frac_bits)


def floats_near(fmt: FixedFormat) -> st.SearchStrategy[float]:
    """Any float, with extra weight on the format's range, its ties and its edges."""
    ulp = 2.0**-fmt.frac_bits
    top = 2.0 ** (fmt.int_bits - 1)
    ties = st.integers(-(1 << 20), 1 << 20).map(lambda n: (n + 0.5) * ulp)
    return st.one_of(
        st.floats(),
        st.floats(-2 * top, 2 * top),
        ties,
        st.sampled_from([top, -top, top - ulp, -top - ulp, top - ulp / 2, -top - ulp / 2]),
        st.floats(-ulp * 4, ulp * 4),
    )


def sample_floats(fmt: FixedFormat, count: int, seed: int = 0) -> list[float]:
    """Reproducible floats for co-simulation: specials, the format's range, ties, tiny values."""
    rng = random.Random(seed)
    ulp = 2.0**-fmt.frac_bits
    top = 2.0 ** (fmt.int_bits - 1)
    specials = [0.0, -0.0, 1.0, -1.0, top, -top, top - ulp, -top - ulp, ulp / 2, 1.5 * ulp]
    specials += [float("inf"), float("-inf"), float("nan"), 5e-324, -5e-324, 1e300, -1e-300]
    draws = [
        lambda: rng.uniform(-2 * top, 2 * top),
        lambda: (rng.randint(-(1 << 20), 1 << 20) + 0.5) * ulp,
        lambda: rng.uniform(-1, 1) * ulp * 2.0 ** rng.randint(-4, 60),
        lambda: rng.choice((-1, 1)) * rng.random() * 2.0 ** rng.randint(-1074, 1023),
    ]
    return specials + [rng.choice(draws)() for _ in range(count - len(specials))]
