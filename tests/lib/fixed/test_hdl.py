"""The float ↔ fixed MyHDL blocks against their models: MyHDL simulation and GHDL co-simulation."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from myhdl import Signal, block, delay, instance, intbv

from rfc.lib.fixed import FixedFormat, fixed_to_float, float_to_bits, float_to_fixed
from rfc.lib.fixed.hdl import fixed_to_float as fixed_to_float_block
from rfc.lib.fixed.hdl import float_to_fixed as float_to_fixed_block
from rfc.toolchain import convert_myhdl, elaboration
from tests.lib.fixed.strategies import floats_near, formats, sample_floats
from tests.support.cosim import run_combinational, signed


@block
def round_trip(bits, raw, overflow, invalid, back, fmt):
    """Both blocks in series: float → fixed → float, every intermediate visible."""
    return float_to_fixed_block(bits, raw, overflow, invalid, fmt), fixed_to_float_block(
        raw, back, fmt
    )


def ports(fmt: FixedFormat):
    return (
        Signal(intbv(0)[64:]),
        fmt.signal(),
        Signal(bool(0)),
        Signal(bool(0)),
        Signal(intbv(0)[64:]),
    )


def expected(values: list[float], fmt: FixedFormat) -> list[tuple[int, bool, bool, int]]:
    rows = []
    for value in values:
        fixed = float_to_fixed(float_to_bits(value), fmt)
        rows.append((fixed.raw, fixed.overflow, fixed.invalid, fixed_to_float(fixed.raw, fmt)))
    return rows


def simulate(values: list[float], fmt: FixedFormat) -> list[tuple[int, bool, bool, int]]:
    bits, raw, overflow, invalid, back = ports(fmt)
    seen = []

    @block
    def bench():
        dut = round_trip(bits, raw, overflow, invalid, back, fmt)

        @instance
        def apply():
            for value in values:
                bits.next = float_to_bits(value)
                yield delay(1)
                seen.append((int(raw.val), bool(overflow), bool(invalid), int(back.val)))

        return dut, apply

    bench().run_sim(quiet=True)
    return seen


@settings(max_examples=25)
@given(st.data())
def test_myhdl_blocks_match_the_models(data):
    fmt = data.draw(formats())
    values = data.draw(st.lists(floats_near(fmt), min_size=1, max_size=40))
    assert simulate(values, fmt) == expected(values, fmt)


@pytest.mark.parametrize(
    "fmt",
    [FixedFormat(55, 53), FixedFormat(8, 4), FixedFormat(100, 90)],
    ids=lambda f: f"Q{f.int_bits}.{f.frac_bits}",
)
def test_converted_vhdl_matches_the_models(tmp_path, fmt):
    values = sample_floats(fmt, 400)
    with elaboration():
        files = convert_myhdl(round_trip(*ports(fmt), fmt), "round_trip", tmp_path / "hdl")
    seen = run_combinational(
        files,
        "round_trip",
        {"bits": [float_to_bits(v) for v in values]},
        ["raw", "overflow", "invalid", "back"],
        tmp_path,
    )
    got = [
        (signed(raw, fmt.width), bool(over), bool(nan), back)
        for raw, over, nan, back in zip(
            seen["raw"], seen["overflow"], seen["invalid"], seen["back"], strict=True
        )
    ]
    assert got == expected(values, fmt)
