"""The cycle semantics docs/schedulers.md promises, pinned on small hand-made scenarios."""

from __future__ import annotations

import numpy as np
import pytest

from rfc.errors import RfcError
from rfc.lib.schedulers.generate import grant_latency
from rfc.lib.schedulers.model import compose_models, make_model, model_of
from rfc.lib.schedulers.model.traffic import Publishers
from rfc.lib.schedulers.spec import Algorithm, CompositionSpec, SchedulerSpec


def grants(model, requests, lasts=None, ready=None):
    """Step a batch-1 model through per-cycle request lists; return the grant of each cycle."""
    out = []
    for k, requesting in enumerate(requests):
        request = np.zeros((1, model.n), dtype=bool)
        request[0, list(requesting)] = True
        last = np.zeros_like(request)
        if lasts is not None:
            last[0, list(lasts[k])] = True
        ok = None if ready is None else np.array([ready[k]])
        out.append(int(model.step(request, last, ok)[0]))
    return out


@pytest.mark.parametrize(
    ("algorithm", "latency"),
    [("LRU", 1), ("NPFP", 1), ("PFP", 1), ("ROEDF", 2), ("LOEDF", 1), ("LST", 1)],
)
def test_grant_latency_of_a_lone_request(algorithm, latency):
    spec = SchedulerSpec.create(algorithm, 5, 10, 40)
    assert grant_latency(spec) == latency


def test_roedf_registers_a_burst_one_request_per_cycle():
    assert grant_latency(SchedulerSpec.create("ROEDF", 6, 10, 40), requests=6) == 7
    assert grant_latency(SchedulerSpec.create("LOEDF", 6, 10, 40), requests=6) == 1


def test_a_composition_adds_the_latencies():
    spec = CompositionSpec.create(
        "LRU", [SchedulerSpec.create("LST", 2, 5, 20), SchedulerSpec.create("ROEDF", 2, 5, 20)]
    )
    assert grant_latency(spec) == 3


def test_roedf_pauses_the_holder_one_cycle_per_arrival_and_resumes_it():
    model = make_model("ROEDF", 2, [8, 8], [10, 50])
    seen = grants(model, [{0}] * 4 + [{0, 1}] * 4)
    assert seen == [-1, -1, 0, 0, 0, -1, 0, 0]


def test_loedf_preempts_at_once_for_an_earlier_deadline_only():
    model = make_model("LOEDF", 3, [8, 8, 8], [40, 10, 90])
    seen = grants(model, [{0}] * 3 + [{0, 1}] * 3 + [{0, 1, 2}] * 2)
    assert seen == [-1, 0, 0, 0, 1, 1, 1, 1]


def test_lst_equal_slacks_swap_the_grant_every_two_cycles():
    # Equal slack at arrival: the holder keeps its slack while it sends, the waiting message
    # loses one a cycle. On the tie the holder keeps the grant; one cycle later the waiting
    # message is strictly more urgent and takes it (the paper's laxity ties).
    model = make_model("LST", 2, [20, 20], [30, 30])
    seen = grants(model, [{0}] + [{0, 1}] * 7)
    assert seen == [-1, 0, 0, 1, 1, 0, 0, 1]


def test_lst_waiting_message_overtakes_when_its_slack_runs_lower():
    # Input 1 arrives with slack 2 below the holder's: it takes over on the next cycle.
    model = make_model("LST", 2, [20, 20], [40, 38])
    seen = grants(model, [{0}, {0}, {0, 1}, {0, 1}, {0, 1}])
    assert seen == [-1, 0, 0, 1, 1]


def test_lru_serves_the_least_recently_granted_requester():
    model = make_model("LRU", 3, 1, 5)
    # One-beat messages (tlast on every beat): 0 granted first, then 1 and 2 before 0 again.
    requests = [{0, 1, 2}] * 7
    lasts = [{0, 1, 2}] * 7
    assert grants(model, requests, lasts) == [-1, 0, 1, 2, 0, 1, 2]


def test_non_preemptive_grant_holds_through_a_stall_until_tlast():
    model = make_model("NPFP", 2, 3, 9)
    requests = [{1}, {0, 1}, {0, 1}, {0, 1}, {0, 1}, {0}]
    lasts = [set(), set(), set(), {1}, set(), set()]
    ready = [True, True, False, True, True, True]
    assert grants(model, requests, lasts, ready) == [-1, 1, -1, 1, 0, 0]


def test_composition_alternates_between_its_children():
    children = [make_model("PFP", 2, 1, 5), make_model("PFP", 2, 1, 5)]
    model = compose_models("LRU", children)
    requests = [{0, 1, 2, 3}] * 6
    seen = grants(model, requests, lasts=requests)
    assert seen[2:] == [0, 2, 0, 2]


def test_per_replicate_timing_gives_independent_replicates():
    transfer = np.array([[4, 4], [4, 4]])
    deadline = np.array([[10, 50], [50, 10]])
    model = make_model("LOEDF", 2, transfer, deadline, batch=2)
    request = np.ones((2, 2), dtype=bool)
    last = np.zeros((2, 2), dtype=bool)
    model.step(request, last)
    assert model.step(request, last).tolist() == [0, 1]


def test_publishers_hold_requests_until_their_last_beat():
    publishers = Publishers(np.array([[3]]), gap=np.array([[2]]))
    seen = []
    for grant in [0, -1, 0, 0, -1, -1, 0]:
        seen.append((bool(publishers.request[0, 0]), bool(publishers.last[0, 0])))
        publishers.advance(np.array([grant]))
    assert seen == [
        (True, False),
        (True, False),
        (True, False),
        (True, True),
        (False, False),
        (False, False),
        (True, False),
    ]


def test_model_of_a_spec_uses_its_exact_constants():
    spec = SchedulerSpec.create("LST", 3, [1, 2, 3], [7, 8, 9], counter_bits=12)
    model = model_of(spec, batch=4)
    assert model.transfer.shape == (4, 3)
    assert model.deadline[3].tolist() == [7, 8, 9]


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: make_model("EDF", 4), "unknown scheduling algorithm 'EDF'"),
        (lambda: make_model("LST", 0), "between 1 and 1024 inputs, not 0"),
        (lambda: make_model("LST", 4, [1, 2, 3]), "expected a scalar, [N] = [4]"),
        (lambda: make_model("LST", 2, 0), "at least 1 cycle"),
        (lambda: make_model("LOEDF", 2, 100, 200, counter_bits=8), "counter width 8 bits"),
        (lambda: compose_models("LRU", [make_model("LST", 2)]), "at least two schedulers"),
    ],
)
def test_bad_parameters_are_user_errors(call, message):
    with pytest.raises(RfcError) as caught:
        call()
    assert message in str(caught.value)


def test_unknown_algorithm_suggests_the_closest():
    with pytest.raises(RfcError) as caught:
        SchedulerSpec.create("LOEFD", 4)
    assert "LOEDF" in str(caught.value.hint)


def test_every_algorithm_is_described():
    assert all(algorithm.description for algorithm in Algorithm)
