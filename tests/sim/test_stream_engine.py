"""The C++ stream engine replays as the cocotb harness does.

The same random bag goes through the multi-type example's Verilog twice: with the DMA streams
driven by cocotbext-axi in cocotb (`simulate_with_ghdl(..., simulator="verilator")`, the
harness `rfc sim` used before) and by the C++ engine (`simulate_with_engine`), with the same
seeded idle cycles and backpressure. Images, scans and twists carry strings and sequences of
every length modulo the bus width. Both must publish the same messages in the same order, the
very bytes rosbags serialized, with the same account. Messages far apart get the same stamps;
messages closer together than the logic needs wait in the queues, and then an output may take
the stamp of the next input in one harness and not the other: their drivers do not move beats
on exactly the same cycles.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rfc.driver import compile_spec
from rfc.lower.hardware import simulation_top
from rfc.lower.runtime_plan import DesignPlan
from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from rfc.runtime.core import QueueConfig, Runtime
from rfc.runtime.stall import DEFAULT_STALL_CYCLES
from rfc.sim.hardware import simulate_with_ghdl
from rfc.sim.settings import ReplaySettings
from rfc.sim.stream_engine import simulate_with_engine
from tests.examples.multi_type.test_system import SPEC, TOPICS, image, scan, twist


def random_bag(path: Path, count: int, spacing: int) -> list[tuple[str, int, bytes]]:
    """Messages of the three types, `spacing` ns apart, frame ids of every length modulo 8."""
    rng = np.random.default_rng(spacing)
    types = message_types("ros2")
    makers = {"/camera/image": image, "/scan": scan, "/cmd_vel": twist}
    messages = []
    for index in range(count):
        topic = list(makers)[int(rng.integers(3))]
        kind = TOPICS[topic][0]
        values = makers[topic](rng)
        values["header"]["frame_id"] = "f" * (index % 9)
        data = types.serialize(types.build(kind, values), kind)
        messages.append((topic, spacing * (index + 1), data))
    write_bag(path, types, {t: k for t, (k, _) in TOPICS.items()}, messages)
    return messages


@pytest.mark.slow
@pytest.mark.parametrize("spacing", [200, 50_000], ids=["queued", "apart"])
def test_the_engine_replays_a_random_bag_as_the_cocotb_harness_does(tmp_path, spacing):
    bag = tmp_path / "in.mcap"
    messages = random_bag(bag, 24, spacing)
    design = compile_spec(SPEC)
    top = simulation_top(design, tmp_path / "hdl")
    topics = {topic: topic for topic in TOPICS}
    settings = ReplaySettings(drain_cycles=200, stall_cycles=DEFAULT_STALL_CYCLES, seed=3)
    harness = simulate_with_ghdl(
        design,
        bag,
        topics,
        top,
        tmp_path,
        queues=QueueConfig(),
        simulator="verilator",
        settings=settings,
    )
    runtime = Runtime(DesignPlan(design), QueueConfig())
    types = message_types("ros2")
    published = simulate_with_engine(
        runtime,
        read_bag(bag, types, topics),
        top,
        clock_mhz=design.project.clock_mhz,
        settings=settings,
    )
    assert [(p.topic, p.data) for p in published] == [(p.topic, p.data) for p in harness.published]
    assert runtime.account.to_json() == harness.account.to_json()
    assert runtime.account.dropped == {}
    renamed = {t: out for t, (_, out) in TOPICS.items()}
    assert sorted((p.topic, p.data) for p in published) == sorted(
        (renamed[t], data) for t, _, data in messages
    )
    if spacing > 1000 * settings.drain_cycles / design.project.clock_mhz:
        assert published == harness.published  # the stamps too
