"""Model ≡ GHDL simulation of the converted VHDL (cocotb) on every cycle, and the properties.

For each design (six algorithms, one composition) and N ∈ {2, 3, 8, 33}: 2,500 cycles of random
traffic (random arrivals and lengths, a channel that stalls 10% of cycles) recorded from the
model and replayed on the VHDL; the grant must be one-hot (or zero) and equal to the model's on
every cycle — 10,000 cycles per design —, and the properties are checked on the hardware's own
grants.
"""

from __future__ import annotations

import pytest

from rfc.dse.verify import replay_in_ghdl
from rfc.lib.schedulers.spec import SchedulerSpec
from rfc.toolchain import CosimError
from tests.support.scheduler_properties import PropertyMonitor
from tests.support.scheduler_traces import (
    COSIM_INPUTS,
    DESIGNS,
    checked_rule,
    cosim_spec,
    record_trace,
)

CYCLES = 2_500


@pytest.mark.slow
@pytest.mark.parametrize("n", COSIM_INPUTS)
@pytest.mark.parametrize("design", DESIGNS)
def test_ghdl_grants_equal_the_model_on_every_cycle(design, n, tmp_path):
    spec = cosim_spec(design, n)
    trace = record_trace(spec, CYCLES, seed=n)
    grants = replay_in_ghdl(spec, trace, tmp_path)
    assert len(grants) == CYCLES
    monitor = PropertyMonitor(checked_rule(design, n), [spec.transfer], [spec.deadline])
    for k in range(CYCLES):
        window = slice(k, k + 1)
        monitor.observe(
            trace.request[window], trace.last[window], grants[window], trace.ready[window]
        )
    assert monitor.counts["completions"] > 120


def test_a_wrong_model_is_reported_with_the_cycle(tmp_path):
    pfp = SchedulerSpec.create("PFP", 3, [4, 4, 4], [9, 9, 9])
    npfp = SchedulerSpec.create("NPFP", 3, [4, 4, 4], [9, 9, 9])
    trace = record_trace(pfp, 400, seed=5)
    with pytest.raises(CosimError, match=r"cycle \d+: model grants \d, GHDL \d"):
        replay_in_ghdl(npfp, trace, tmp_path)
