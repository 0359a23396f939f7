"""The scheduler algorithms' hardware, by name: each algorithm's module registers its parts.

Adding a scheduler is one module that decorates the function building its statechart parts
(Compute Condition and Set Grant, `rfc.lib.schedulers.statechart.PolicyHardware`) with
``@policy(Algorithm.X)``, and one import in `rfc.lib.schedulers.hardware`. Asking for an
algorithm nobody registered is an error naming the ones there are.
"""

from __future__ import annotations

from collections.abc import Callable

from rfc.errors import RfcError
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.lib.schedulers.statechart import PolicyHardware

#: Builds an algorithm's statechart parts for a spec.
PolicyFactory = Callable[[SchedulerSpec], PolicyHardware]

_POLICIES: dict[Algorithm, PolicyFactory] = {}


def policy(algorithm: Algorithm) -> Callable[[PolicyFactory], PolicyFactory]:
    """Register the decorated function as `algorithm`'s hardware."""

    def register(factory: PolicyFactory) -> PolicyFactory:
        if algorithm in _POLICIES:
            raise ValueError(f"two modules register scheduler hardware for {algorithm.value}")
        _POLICIES[algorithm] = factory
        return factory

    return register


def policy_hardware(spec: SchedulerSpec) -> PolicyHardware:
    """The Compute Condition and Set Grant parts of `spec`'s algorithm.

    Raises:
        RfcError: No module registered hardware for the algorithm.
    """
    factory = _POLICIES.get(spec.algorithm)
    if factory is None:
        known = ", ".join(a.value for a in _POLICIES)
        raise RfcError(
            f"no hardware is registered for scheduler {spec.algorithm.value}; "
            f"the registered ones are {known}"
        )
    return factory(spec)


def registered() -> tuple[Algorithm, ...]:
    """The algorithms with hardware, in registration order."""
    return tuple(_POLICIES)
