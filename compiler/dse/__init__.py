"""Design-space exploration of the schedulers (paper §7.2, docs/dse.md).

`datasets` draws the traffic, `kernel` simulates it on the compiled scheduler kernels and
aggregates the metrics as it goes, `engine` runs points in parallel, `metrics` summarizes them
(mean and 95 % confidence interval), `project` and `objective` recommend a scheduler for a
spec, and `tables`, `plots` and `report` write the results.

Layer: beside the IR, which it does not import (a project's traffic comes as plain values). It
reads only the scheduler models of `rfc.lib.schedulers`, checks them with `rfc.toolchain`, and
uses `rfc.cluster`, `rfc.files` and `rfc.errors`.
"""
