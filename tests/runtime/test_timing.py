"""The paper's §4.3 point: a fast topic goes stale behind a slow one in ROS's shared queue."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from rfc.runtime.timing import Traffic, measure, transfer_ns

ROOT = Path(__file__).resolve().parents[2]


def load_tool():
    spec = importlib.util.spec_from_file_location("bench", ROOT / "tools" / "bench_queue_policy.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def bus_of(plan):
    project = plan.design.project
    return {"bus_width": project.bus_width, "clock_mhz": project.clock_mhz}


@pytest.fixture(scope="module")
def setting():
    tool = load_tool()
    plan = tool.runtime_plan()
    data = tool.sample_messages(plan)
    per_subscriber, shared = tool.POLICIES.values()
    image = transfer_ns(len(data["/camera/image"]), 64, 100.0)
    return tool, plan, data, per_subscriber, shared, image


def test_transfer_time_counts_beats_of_the_bus_with_the_chunk_header():
    assert transfer_ns(76, 64, 100.0) == 110  # (8 + 76) / 8 → 11 beats of 10 ns
    assert transfer_ns(76, 8, 100.0) == 840
    assert transfer_ns(76, 64, 100.0, overhead_cycles=5) == 160


def test_bursts_of_images_make_twists_stale_only_in_a_shared_fifo(setting):
    tool, plan, data, per_subscriber, shared, image = setting
    traffic = next(iter(tool.scenarios(data).values()))
    lru = measure(plan, traffic, per_subscriber, 1_000_000_000, **bus_of(plan))
    fifo = measure(plan, traffic, shared, 1_000_000_000, **bus_of(plan))
    twist_lru, twist_fifo = lru["/cmd_vel"], fifo["/cmd_vel"]
    assert twist_lru.arrived == twist_fifo.arrived == twist_lru.delivered == 50
    # per subscriber: a twist waits for at most the image on the DMA (and a scan)
    assert twist_lru.age_ms("max") * 1e6 < image + transfer_ns(len(data["/scan"]), 64, 100.0)
    assert twist_lru.stale == 0
    # shared: it waits behind every image of the burst queued before it
    assert twist_fifo.age_ms("max") * 1e6 > 2 * image
    assert twist_fifo.stale > 0
    assert lru["/camera/image"].delivered == fifo["/camera/image"].delivered == 30


def test_under_overload_only_the_overloading_topic_loses_messages_per_subscriber(setting):
    tool, plan, data, per_subscriber, shared, _ = setting
    traffic = list(tool.scenarios(data).values())[2]
    lru = measure(plan, traffic, per_subscriber, 1_000_000_000, **bus_of(plan))
    fifo = measure(plan, traffic, shared, 1_000_000_000, **bus_of(plan))
    assert lru["/camera/image"].dropped > 0
    assert lru["/cmd_vel"].dropped == lru["/scan"].dropped == 0
    assert fifo["/cmd_vel"].dropped > 0
    assert fifo["/scan"].dropped > 0
    for figures in (lru, fifo):
        for f in figures.values():
            assert f.arrived == f.delivered + f.dropped


def test_messages_arriving_together_are_all_counted(setting):
    _, plan, data, per_subscriber, _, _ = setting
    traffic = [Traffic("/cmd_vel", data["/cmd_vel"], 1_000_000, burst=4)]
    (figures,) = measure(plan, traffic, per_subscriber, 3_000_000, **bus_of(plan)).values()
    assert (figures.arrived, figures.delivered, figures.stale) == (12, 12, 9)
    assert figures.age_ms("max") * 1e6 == 4 * transfer_ns(len(data["/cmd_vel"]), 64, 100.0)
