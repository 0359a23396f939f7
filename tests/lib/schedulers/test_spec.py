"""A scheduler spec: how a composition shares the inputs, and the timing its counters hold."""

import pytest

from rfc.errors import RfcError
from rfc.lib.schedulers.spec import (
    COUNTER_HEADROOM_BITS,
    MAX_COUNTER_BITS,
    MAX_TIMING,
    SchedulerSpec,
    parse_scheduler,
)


def _sizes(text: str, n: int) -> list[int]:
    return [child.n for child in parse_scheduler(text, n).children]


@pytest.mark.parametrize(
    ("text", "n", "sizes"),
    [
        # As evenly as possible; the inputs that do not divide go to the last children.
        ("LRU(LST,LST,LST)", 8, [2, 3, 3]),
        ("LRU(LST,LST,LST)", 9, [3, 3, 3]),
        ("LRU(LST,LST,LST,LST)", 7, [1, 2, 2, 2]),
        # Sized children keep their size; the unsized share what is left.
        ("LRU(PFP,ROEDF:2)", 5, [3, 2]),
        ("LRU(LST:5,LST,LST)", 10, [5, 2, 3]),
        ("LRU(LST:1,LST:3)", 4, [1, 3]),
    ],
)
def test_children_share_the_inputs_as_named(text: str, n: int, sizes: list[int]) -> None:
    assert _sizes(text, n) == sizes


def test_a_nested_composition_shares_its_own_share() -> None:
    spec = parse_scheduler("LRU(LST,PFP(LST,LST:1))", 7)
    inner = spec.children[1]
    assert [child.n for child in spec.children] == [3, 4]
    assert [child.n for child in inner.children] == [3, 1]


@pytest.mark.parametrize(
    ("text", "n"), [("LRU(LST:1,LST:1)", 4), ("LRU(LST:4,LST)", 4), ("LRU(LST,LST,LST)", 2)]
)
def test_sizes_that_do_not_add_up_are_refused(text: str, n: int) -> None:
    with pytest.raises(RfcError, match=f"must share the {n} inputs"):
        parse_scheduler(text, n)


@pytest.mark.parametrize("algorithm", ["LOEDF", "LST"])
def test_the_longest_deadline_fits_the_default_counters_with_their_headroom(algorithm: str) -> None:
    # The counters are biased by H = 2^(bits-1) and must hold D + T below it, with
    # COUNTER_HEADROOM_BITS more than the largest constant needs (room for lateness).
    spec = SchedulerSpec.create(algorithm, 2, [1, MAX_TIMING], [MAX_TIMING, MAX_TIMING])
    assert spec.counter_bits <= MAX_COUNTER_BITS
    assert 1 << (spec.counter_bits - 1) > MAX_TIMING + MAX_TIMING
    assert 1 << (spec.counter_bits - 1 - COUNTER_HEADROOM_BITS) > MAX_TIMING


@pytest.mark.parametrize(("transfer", "deadline"), [(5, MAX_TIMING + 1), (MAX_TIMING + 1, 5)])
def test_a_timing_beyond_the_widest_counters_is_refused_with_a_hint(
    transfer: int, deadline: int
) -> None:
    with pytest.raises(RfcError, match="too long for the scheduler's 48-bit counters") as error:
        SchedulerSpec.create("LOEDF", 1, transfer, deadline)
    assert error.value.hint == f"give a deadline (or period) of at most {MAX_TIMING} cycles"
