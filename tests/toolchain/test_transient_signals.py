"""`transient_signals`: MyHDL forgets the signals of work that is over, and only those.

MyHDL resets every signal it knows at the end of every simulation; a signal it keeps for ever
makes every later simulation of the process slower and stays in memory.
"""

from __future__ import annotations

from typing import Any

import pytest
from myhdl import ConcatSignal, Signal, block, delay, instance, intbv
from myhdl import _simulator as myhdl_simulator

from rfc.toolchain import transient_signals


def known(signal: Any) -> bool:
    return any(s is signal for s in myhdl_simulator._signals)


def run_swap_bench(values: list[int]) -> list[int]:
    """Swap the bytes of 16-bit words through a shadow signal (a concatenation of slices)."""
    word = Signal(intbv(0)[16:])
    swapped = ConcatSignal(word(8, 0), word(16, 8))
    seen: list[int] = []

    @block
    def bench() -> Any:
        @instance
        def drive() -> Any:
            for value in values:
                word.next = value
                yield delay(1)
                seen.append(int(swapped))

        return drive

    bench().run_sim(quiet=True)
    return seen


def test_signals_created_inside_are_forgotten_and_those_before_kept():
    before = Signal(bool(0))
    with transient_signals():
        outer = Signal(bool(0))
        with transient_signals():
            inner = Signal(bool(0))
        assert known(outer)
        assert not known(inner)
    assert known(before)
    assert not known(outer)


def test_a_bench_built_and_run_inside_simulates_shadow_signals_each_time():
    for values in ([0x1234, 0xABCD], [0x00FF, 0x8001, 0]):
        with transient_signals():
            assert run_swap_bench(values) == [((v & 0xFF) << 8) | (v >> 8) for v in values]


def failing_bench() -> None:
    Signal(bool(0))
    raise RuntimeError("the bench failed")


def test_the_signals_are_forgotten_when_the_work_raises():
    count = len(myhdl_simulator._signals)
    with pytest.raises(RuntimeError), transient_signals():
        failing_bench()
    assert len(myhdl_simulator._signals) == count
