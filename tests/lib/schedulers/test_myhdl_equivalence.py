"""Model ≡ MyHDL simulation on every cycle, on random traffic, N ∈ {2, 3, 8, 33}.

Each design replays 10,000 cycles in MyHDL's simulator (3,000 at N = 2, 3 and 8, 1,000 at
N = 33, whose simulation is the slowest), for every algorithm and the composition. The GHDL
co-simulation of the converted VHDL is in tests/hdl/schedulers.
"""

from __future__ import annotations

import pytest

from rfc.lib.schedulers.spec import SchedulerSpec
from tests.support.myhdl_sim import simulate_myhdl
from tests.support.scheduler_properties import PropertyMonitor
from tests.support.scheduler_traces import (
    COSIM_INPUTS,
    DESIGNS,
    checked_rule,
    cosim_spec,
    first_difference,
    record_trace,
)

CYCLES = {2: 3_000, 3: 3_000, 8: 3_000, 33: 1_000}


def test_every_design_replays_ten_thousand_cycles():
    assert set(CYCLES) == set(COSIM_INPUTS)
    assert sum(CYCLES.values()) >= 10_000


@pytest.mark.slow
@pytest.mark.parametrize("n", COSIM_INPUTS)
@pytest.mark.parametrize("design", DESIGNS)
def test_myhdl_grants_equal_the_model_on_every_cycle(design, n):
    spec = cosim_spec(design, n)
    trace = record_trace(spec, CYCLES[n], seed=100 + n)
    grants = simulate_myhdl(spec, trace)
    assert first_difference(trace.grant, grants, trace) is None, f"{spec.name}"
    monitor = PropertyMonitor(checked_rule(design, n), [spec.transfer], [spec.deadline])
    for k in range(trace.cycles):
        window = slice(k, k + 1)
        monitor.observe(
            trace.request[window], trace.last[window], grants[window], trace.ready[window]
        )
    assert monitor.counts["completions"] > 50


def test_a_different_algorithm_is_caught_on_the_cycle_it_differs():
    npfp = SchedulerSpec.create("NPFP", 3, [4, 4, 4], [9, 9, 9])
    pfp = SchedulerSpec.create("PFP", 3, [4, 4, 4], [9, 9, 9])
    trace = record_trace(pfp, 400, seed=5)
    difference = first_difference(trace.grant, simulate_myhdl(npfp, trace), trace)
    assert difference is not None
    assert difference.startswith("cycle ")
