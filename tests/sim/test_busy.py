"""Reading the logic's busy bits: wait while they are high, give up after the cap with a warning."""

from __future__ import annotations

from rfc.sim.busy import BusyWatch


def test_busy_until_the_bits_fall():
    watch = BusyWatch(("fk", "fk_pub"), cap=100)
    assert watch.busy(10, 0b01)
    assert watch.busy(99, 0b11)
    assert not watch.busy(105, 0)
    assert watch.warnings == []


def test_a_transfer_restarts_the_cap():
    watch = BusyWatch(("fk",), cap=100)
    assert watch.busy(0, 1)
    watch.completed(90)
    assert watch.busy(150, 1)
    assert watch.warnings == []


def test_after_the_cap_the_bits_are_given_up_on_with_a_warning_naming_the_blocks():
    watch = BusyWatch(("stuck", "fine", "other"), cap=100)
    assert watch.busy(0, 0b101)
    assert not watch.busy(100, 0b101)
    assert len(watch.warnings) == 1
    assert "'stuck', 'other'" in watch.warnings[0]
    assert "'fine'" not in watch.warnings[0]
    assert not watch.busy(1000, 0b101)  # given up on: no second warning
    assert watch.busy(1001, 0b111)  # another block is still watched
    assert len(watch.warnings) == 1


def test_a_bit_that_falls_is_watched_again():
    watch = BusyWatch(("stuck",), cap=10)
    watch.busy(0, 1)
    assert not watch.busy(10, 1)
    assert not watch.busy(11, 0)
    assert watch.busy(12, 1)
    assert not watch.busy(22, 1)
    assert len(watch.warnings) == 2
