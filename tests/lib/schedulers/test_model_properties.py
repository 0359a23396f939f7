"""The properties of issue 5 over 1,000,000 random cycles per algorithm, on the vectorized model.

100 replicates x 10,000 cycles, each replicate with its own random T_i and D_i, random arrivals
and a channel that stalls 10% of cycles. The monitor derives priorities from the paper's
definitions and the observable channel only. The last tests show each check catches a
scheduler that breaks it.
"""

from __future__ import annotations

import numpy as np
import pytest

from rfc.lib.schedulers.model import compose_models, make_model
from rfc.lib.schedulers.model.traffic import Publishers
from rfc.lib.schedulers.spec import Algorithm
from tests.support.scheduler_properties import PropertyError, PropertyMonitor

REPLICATES = 100
CYCLES = 10_000
N = 7


def random_timing(rng, n=N):
    transfer = rng.integers(1, 16, size=(REPLICATES, n))
    deadline = transfer + rng.integers(1, 60, size=(REPLICATES, n))
    return transfer, deadline


def run(model, monitor, rng, cycles=CYCLES, max_gap=3 * N):
    publishers = Publishers(model.transfer, max_gap=max_gap, rng=rng)
    for _ in range(cycles):
        request, last = publishers.request, publishers.last
        ready = rng.random(model.batch) >= 0.1
        grant = model.step(request, last, ready)
        monitor.observe(request, last, grant, ready)
        publishers.advance(grant)
    return monitor.counts


@pytest.mark.slow
@pytest.mark.parametrize("algorithm", list(Algorithm))
def test_properties_hold_over_a_million_cycles(algorithm):
    rng = np.random.default_rng(list(Algorithm).index(algorithm))
    transfer, deadline = random_timing(rng)
    model = make_model(algorithm, N, transfer, deadline, batch=REPLICATES)
    counts = run(model, PropertyMonitor(algorithm, transfer, deadline), rng)
    assert REPLICATES * CYCLES >= 1_000_000
    assert counts["completions"] > 50_000
    if algorithm.preemptive:
        assert counts["moves"] > 500, "the traffic must make the scheduler preempt"


@pytest.mark.slow
def test_a_composition_keeps_the_generic_properties():
    rng = np.random.default_rng(7)
    t1, d1 = random_timing(rng, 3)
    t2, d2 = random_timing(rng, 4)
    children = [
        make_model("LOEDF", 3, t1, d1, batch=REPLICATES),
        make_model("LST", 4, t2, d2, batch=REPLICATES),
    ]
    model = compose_models("LRU", children)
    monitor = PropertyMonitor(None, model.transfer, model.deadline)
    counts = run(model, monitor, rng, cycles=CYCLES // 2)
    assert counts["completions"] > 20_000


def broken_against(rule, algorithm, cycles=3_000, max_gap=3 * N, n=N, **timing):
    rng = np.random.default_rng(3)
    transfer, deadline = random_timing(rng, n)
    model = make_model(algorithm, n, transfer, deadline, batch=REPLICATES, **timing)
    with pytest.raises(PropertyError) as caught:
        run(model, PropertyMonitor(rule, transfer, deadline), rng, cycles, max_gap)
    return str(caught.value)


def test_a_preemption_breaks_a_non_preemptive_rule():
    assert "non-preemptive grant moved" in broken_against(Algorithm.NPFP, "PFP")


def test_a_non_lowest_index_breaks_fixed_priority():
    assert "fixed priority granted" in broken_against(Algorithm.PFP, "LOEDF")


def test_fixed_priority_starves_beyond_the_lru_bound():
    assert "more than N-1" in broken_against(Algorithm.LRU, "NPFP", cycles=6_000)


def test_least_slack_is_not_earliest_deadline():
    assert "not strictly more urgent" in broken_against(Algorithm.LOEDF, "LST")


def test_roedf_beyond_its_horizon_leaves_the_edf_rule():
    # Overloaded, with 8-bit counters, pending deadlines spread over more than half the
    # timer's circle: the wrap-around comparison then inverts (documented horizon).
    assert "not strictly more urgent" in broken_against(
        Algorithm.ROEDF, "ROEDF", cycles=6_000, max_gap=0, n=24, counter_bits=8
    )
