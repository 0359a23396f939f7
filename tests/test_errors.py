"""`located`: the compiler gives lib's errors the spec element they concern."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError, SourceLocation, located

BLOCK = SourceLocation("spec.yaml", 12, 5)


def test_an_error_without_a_location_gets_the_block_s():
    with pytest.raises(RfcError) as error, located(BLOCK):
        raise RfcError("bus width 16 is not supported", hint="use 8, 32 or 64")
    assert (
        str(error.value) == "spec.yaml:12:5: bus width 16 is not supported\n  hint: use 8, 32 or 64"
    )


def test_an_error_that_has_a_location_keeps_it():
    own = SourceLocation("spec.yaml", 3, 1)
    with pytest.raises(RfcError) as error, located(BLOCK):
        raise RfcError("unknown type", location=own)
    assert error.value.location == own


def test_other_exceptions_pass_unchanged():
    with pytest.raises(ValueError, match="a bug"), located(BLOCK):
        raise ValueError("a bug")
