"""Replay a trace on a scheduler's MyHDL description in MyHDL's own simulator."""

from __future__ import annotations

import numpy as np
from myhdl import block, delay, instance

from rfc.dse.trace import Trace, bits_to_int, one_hot_index
from rfc.lib.schedulers.hardware import scheduler_top, top_ports
from rfc.lib.schedulers.spec import AnySchedulerSpec
from rfc.toolchain import elaboration


def simulate_myhdl(spec: AnySchedulerSpec, trace: Trace) -> np.ndarray:
    """The hardware's grant (index or -1) on every cycle of `trace` (after one reset cycle)."""
    clk, rst, request, last, ready, grant = top_ports(spec)
    requests = [bits_to_int(row) for row in trace.request]
    lasts = [bits_to_int(row) for row in trace.last]
    readies = [bool(r) for r in trace.ready]
    grants: list[int] = []

    @block
    def bench():
        dut = scheduler_top(spec)(clk, rst, request, last, ready, grant)

        @instance
        def drive():
            rst.next = 1
            yield delay(1)
            clk.next = 1
            yield delay(1)
            clk.next = 0
            rst.next = 0
            for k in range(len(requests)):
                request.next = requests[k]
                last.next = lasts[k]
                ready.next = readies[k]
                yield delay(1)
                grants.append(one_hot_index(int(grant.val)))
                clk.next = 1
                yield delay(1)
                clk.next = 0

        return dut, drive

    with elaboration():  # MyHDL's own elaboration reads every caller's source context
        sim = bench()
        sim.run_sim(quiet=1)
        sim.quit_sim()
    return np.asarray(grants)
