"""A project's publishers as DSE traffic, its recommendation, and resolve-scheduler."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from rfc.driver import compile_spec
from rfc.dse.objective import parse_objective
from rfc.dse.project import candidates, project_traffic, recommend
from rfc.errors import RfcError
from rfc.passes.pipeline import BUILD_PIPELINE
from rfc.passes.resolve_scheduler import ResolveScheduler

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
HUB = EXAMPLES / "sensor_hub" / "SensorHub.yaml"
TIMING = "completed,missed,max_lateness"


def traffic_of(design, horizon=None):
    return project_traffic(design.project.name, design.infrastructure.scheduler.inputs, horizon)


@pytest.fixture(scope="module")
def hub():
    return compile_spec(HUB)


def test_the_traffic_comes_from_layouts_and_timing(hub):
    traffic = traffic_of(hub)
    assert traffic.publishers[:2] == ("Pose_pub", "Twist_pub")
    # PoseWithCovariance: 4 + 7*8 + 36*8 = 348 bytes + an 8-byte chunk header on 64-bit beats
    assert traffic.transfer == (45, 44, 44, 8, 5, 8)
    assert traffic.period == (200, 200, 400, 50, 50, 100)
    assert traffic.deadline == (200, 200, 400, 30, 20, 25)
    assert traffic.idle == (155, 156, 356, 42, 45, 92)
    assert traffic.cycles == 10_000


def test_deadline_driven_schedulers_win_the_hub(hub):
    recommendation = recommend(traffic_of(hub), parse_objective(TIMING))
    ranking = {c.scheduler: c for c in recommendation.ranking}
    assert set(ranking) == set(candidates(6))
    assert recommendation.ranking[0].metrics["missed"] == 0
    assert ranking["NPFP"].metrics["missed"] > 0.2  # Pose_pub, declared first, hogs it
    assert recommendation.scheduler == "LOEDF"  # tied with LST; listed first
    assert recommendation.reasons[-1] == "ties on every criterion with LST; listed first"


def test_a_publisher_without_period_is_named():
    design = compile_spec(EXAMPLES / "multi_type" / "MultiType.yaml")
    with pytest.raises(RfcError) as caught:
        traffic_of(design)
    assert "publishers Image_pub, Scan_pub, Twist_pub of project 'MultiType' have no period" in (
        str(caught.value)
    )
    assert "period" in str(caught.value.hint)


def test_resolve_scheduler_records_the_choice_and_its_reasons(hub):
    design = ResolveScheduler(objective=TIMING).apply(hub)
    scheduler = design.infrastructure.scheduler
    assert scheduler.algorithm == "LOEDF"
    assert scheduler.reason.startswith("rfc dse: accelerators that completed a message: 6")
    assert ResolveScheduler().apply(design) is design  # a concrete algorithm is kept


def test_without_periods_lru_and_for_one_publisher_pfp():
    several = compile_spec(EXAMPLES / "multi_type" / "MultiType.yaml")
    several = replace(
        several,
        infrastructure=replace(
            several.infrastructure,
            scheduler=replace(several.infrastructure.scheduler, algorithm="auto"),
        ),
    )
    assert ResolveScheduler().apply(several).infrastructure.scheduler.algorithm == "LRU"
    one = compile_spec(EXAMPLES / "rotation_converter" / "RotationConverterNode.yaml")
    assert one.infrastructure.scheduler.algorithm == "auto"
    assert ResolveScheduler().apply(one).infrastructure.scheduler.algorithm == "PFP"


def test_build_runs_resolve_scheduler_last():
    assert BUILD_PIPELINE[-1].name == "resolve-scheduler"


def with_periods(design, periods):
    scheduler = design.infrastructure.scheduler
    inputs = tuple(
        replace(i, period=p, deadline=None) for i, p in zip(scheduler.inputs, periods, strict=True)
    )
    infrastructure = replace(design.infrastructure, scheduler=replace(scheduler, inputs=inputs))
    return replace(design, infrastructure=infrastructure)


def test_long_periods_get_a_horizon_of_ten_messages_of_the_slowest_publisher(hub):
    # 25-33 ms at 100 MHz: a fixed 2 ms horizon would see one message of each publisher
    periods = (2_500_000, 2_600_000, 2_700_000, 2_800_000, 3_000_000, 3_300_000)
    traffic = traffic_of(with_periods(hub, periods))
    assert traffic.cycles >= 10 * 3_300_000
    assert min(traffic.messages) >= 10
    assert traffic.messages[0] == -(-traffic.cycles // 2_500_000)


def test_a_horizon_given_is_the_horizon_simulated(hub):
    assert traffic_of(hub, horizon=12_345).cycles == 12_345
    recommendation = recommend(traffic_of(hub, horizon=400), parse_objective(TIMING), ["LRU"])
    assert recommendation.traffic.messages == (2, 2, 1, 8, 8, 4)
