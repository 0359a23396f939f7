"""`rfc sim SPEC --bag DIR --out DIR`: one output per bag, the single run's, on Dask too."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.runtime.support import pose_messages, system_copy
from tests.support.cli import run_rfc
from tests.support.dask_cluster import dask_scheduler  # noqa: F401 (a fixture)

ROOT = Path(__file__).resolve().parents[2]
POSE = "geometry_msgs/msg/PoseWithCovarianceStamped"
TO_SOFTWARE = ("type: MyHDL", "type: ROS-SW")


def messages_of(path: Path) -> list[tuple[str, int, bytes]]:
    return [(m.topic, m.timestamp_ns, bytes(m.data)) for m in read_bag(path, message_types("ros2"))]


@pytest.fixture
def batch(tmp_path):
    """A software system and a directory of two good bags and one of the wrong message type."""
    types = message_types("ros2")
    bags = tmp_path / "bags"
    bags.mkdir()
    for name, count in (("a.mcap", 4), ("b.db3", 3)):
        messages = pose_messages(types, count)
        rows = [(m.topic, m.timestamp_ns, m.data) for m in messages]
        write_bag(bags / name, types, {"/amcl_pose": POSE}, rows)
    point = "geometry_msgs/msg/Point"
    data = types.serialize(types.build(point, {"x": 1.0, "y": 2.0, "z": 3.0}), point)
    write_bag(bags / "c.mcap", types, {"/amcl_pose": point}, [("/amcl_pose", 1, data)])
    (bags / "notes.txt").write_text("not a bag")
    return system_copy(tmp_path, "pose_mixed.yaml", TO_SOFTWARE), bags


def test_each_bag_gives_the_single_runs_output_here_and_on_a_cluster(
    tmp_path,
    batch,
    dask_scheduler,  # noqa: F811
):
    spec, bags = batch
    args = ("sim", spec, "--bag", bags, "--queue", "shared-fifo", "--json")
    serial = run_rfc(*args, "--out", tmp_path / "serial", cwd=ROOT)
    clustered = run_rfc(*args, "--out", tmp_path / "cluster", "--cluster", dask_scheduler, cwd=ROOT)
    single = run_rfc(
        "sim", spec, "--bag", bags / "a.mcap", "--out", tmp_path / "a.mcap",
        "--queue", "shared-fifo", "--json", cwd=ROOT,
    )  # fmt: skip
    assert single.returncode == 0, single.stderr
    for result, out in ((serial, "serial"), (clustered, "cluster")):
        assert result.returncode == 1  # the Point bag fails; the others are kept
        assert "1 of 3 replays failed (bag c.mcap: " in result.stderr
        assert "topic '/amcl_pose' of bag '" in result.stderr
        document = json.loads(result.stdout)
        assert [Path(a["bag"]).name for a in document["bags"]] == ["a.mcap", "b.db3"]
        assert [a["published"] for a in document["bags"]] == [
            {"/pose_cleared": 4},
            {"/pose_cleared": 3},
        ]
        assert [f["job"] for f in document["failed"]] == ["bag c.mcap"]
        assert sorted(p.name for p in (tmp_path / out).iterdir()) == ["a.mcap", "b.db3"]
        assert messages_of(tmp_path / out / "a.mcap") == messages_of(tmp_path / "a.mcap")
    first = json.loads(single.stdout)
    assert json.loads(clustered.stdout)["bags"][0]["published"] == first["published"]
    assert messages_of(tmp_path / "cluster" / "b.db3") == messages_of(tmp_path / "serial" / "b.db3")


def test_a_directory_without_bags_is_one_clear_error(tmp_path, batch):
    spec, _ = batch
    empty = tmp_path / "empty"
    empty.mkdir()
    result = run_rfc("sim", spec, "--bag", empty, "--out", tmp_path / "o", cwd=ROOT)
    assert result.returncode == 1
    assert f"--bag '{empty}' holds no bag" in result.stderr
    assert not (tmp_path / "o").exists()


def test_jobs_with_one_bag_is_refused(tmp_path, batch):
    spec, bags = batch
    result = run_rfc(
        "sim", spec, "--bag", bags / "a.mcap", "--out", tmp_path / "o.mcap", "--jobs", "2", cwd=ROOT
    )
    assert result.returncode == 1
    assert "--jobs and --cluster spread the bags of a directory" in result.stderr
    assert not (tmp_path / "o.mcap").exists()
