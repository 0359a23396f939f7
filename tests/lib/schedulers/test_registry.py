"""The scheduler registry: every algorithm has its own hardware, and a missing one is an error."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError
from rfc.lib.schedulers import (
    hardware,  # noqa: F401  (registers every algorithm's module)
    registry,
)
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec


def test_every_algorithm_has_hardware_of_its_own():
    assert set(registry.registered()) == set(Algorithm)
    parts = {a: registry.policy_hardware(SchedulerSpec.create(a, 4)) for a in Algorithm}
    assert parts[Algorithm.PFP].preemptive
    assert not parts[Algorithm.NPFP].preemptive
    assert parts[Algorithm.LST] != parts[Algorithm.LOEDF]


def test_an_algorithm_without_hardware_is_an_error_naming_those_there_are(monkeypatch):
    policies = {a: f for a, f in registry._POLICIES.items() if a is not Algorithm.LST}
    monkeypatch.setattr(registry, "_POLICIES", policies)
    with pytest.raises(RfcError) as caught:
        registry.policy_hardware(SchedulerSpec.create(Algorithm.LST, 4))
    assert "no hardware is registered for scheduler LST" in str(caught.value)
    assert "LOEDF" in str(caught.value)


def test_registering_an_algorithm_twice_is_refused():
    with pytest.raises(ValueError, match="two modules register scheduler hardware for LRU"):
        registry.policy(Algorithm.LRU)(lambda spec: None)
