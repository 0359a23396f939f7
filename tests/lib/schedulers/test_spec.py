"""How a composition's name shares the inputs among its children (`parse_scheduler`)."""

import pytest

from rfc.errors import RfcError
from rfc.lib.schedulers.spec import parse_scheduler


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
