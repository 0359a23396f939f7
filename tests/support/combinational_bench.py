"""cocotb bench: apply input vectors to a combinational block and record its outputs."""

from __future__ import annotations

import json
import os
from pathlib import Path

import cocotb
from cocotb.triggers import Timer


@cocotb.test()
async def apply_vectors(dut):
    job = json.loads(Path(os.environ["RFC_JOB"]).read_text())
    inputs = job["inputs"]
    count = len(next(iter(inputs.values())))
    seen = {name: [] for name in job["outputs"]}
    for index in range(count):
        for name, values in inputs.items():
            getattr(dut, name).value = values[index]
        await Timer(1, unit="ns")
        for name in seen:
            seen[name].append(int(getattr(dut, name).value))
    Path(job["result"]).write_text(json.dumps({"outputs": seen}))
