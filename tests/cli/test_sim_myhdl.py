"""`rfc sim --backend myhdl` on generated systems: the same bag as GHDL, or a clear refusal.

The quaternion example (a pipelined MyHDL core) and the multi-type example (strings and
sequences through the publishers' buffers) run in MyHDL's simulator — converters, manager,
scheduler, accelerators and the structural top as MyHDL instances — with random idle and
backpressure, and must give the very bag and account GHDL gives on the VHDL. A logic with a
VHDL accelerator is refused, naming it, and nothing is written.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.examples.multi_type.test_system import TOPICS, image, scan, twist
from tests.lower.system.systems import point_system, point_vhdl, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
QUATERNION = "geometry_msgs/msg/Quaternion"


def both_backends(spec: Path, bag: Path, folder: Path, *extra: str) -> dict[str, dict]:
    """The account of each backend (its output is folder/<backend>.mcap)."""
    accounts = {}
    for backend, option in (("ghdl", ("--simulator", "ghdl")), ("myhdl", ("--backend", "myhdl"))):
        out = folder / f"{backend}.mcap"
        result = run_rfc("sim", spec, "--bag", bag, "--out", out, *option, *extra, "--json")
        assert result.returncode == 0, result.stderr
        accounts[backend] = json.loads(result.stdout) | {"out": ""}
    return accounts


def outputs(path: Path) -> list[tuple[str, int, bytes]]:
    return [(m.topic, m.timestamp_ns, m.data) for m in read_bag(path, message_types("ros2"))]


def test_the_quaternion_example_gives_ghdls_bag_in_myhdl(tmp_path):
    types = message_types("ros2")
    rng = np.random.default_rng(3)
    quaternions = rng.normal(size=(5, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    inputs = [
        ("/imu/orientation", 2000 * (i + 1) + 100 * (i % 2),
         types.serialize(types.build(QUATERNION, dict(zip("xyzw", map(float, q), strict=True))),
                         QUATERNION))
        for i, q in enumerate(quaternions)
    ]  # fmt: skip
    bag = tmp_path / "q.mcap"
    write_bag(bag, types, {"/imu/orientation": QUATERNION}, inputs)
    spec = ROOT / "examples/quaternion_to_euler/project.yaml"
    accounts = both_backends(spec, bag, tmp_path, "--seed", "7")
    assert accounts["ghdl"]["warnings"] == []
    assert accounts["myhdl"] == accounts["ghdl"]
    assert accounts["ghdl"]["published"] == {"/imu/euler": 5}
    assert outputs(tmp_path / "myhdl.mcap") == outputs(tmp_path / "ghdl.mcap")


def test_the_multi_type_example_gives_ghdls_bag_in_myhdl(tmp_path):
    rng = np.random.default_rng(5)
    types = message_types("ros2")
    makers = {"/camera/image": image, "/scan": scan, "/cmd_vel": twist}
    inputs = []
    for index in range(3):
        topic = list(makers)[index % 3]
        kind = TOPICS[topic][0]
        data = types.serialize(types.build(kind, makers[topic](rng)), kind)
        inputs.append((topic, 1_000_000 * (index + 1), data))
    bag = tmp_path / "in.mcap"
    write_bag(bag, types, {topic: kind for topic, (kind, _) in TOPICS.items()}, inputs)
    spec = ROOT / "examples/multi_type/MultiType.yaml"
    accounts = both_backends(spec, bag, tmp_path)
    assert accounts["ghdl"]["warnings"] == []
    assert accounts["myhdl"] == accounts["ghdl"]
    assert sum(accounts["ghdl"]["published"].values()) == 3
    assert outputs(tmp_path / "myhdl.mcap") == outputs(tmp_path / "ghdl.mcap")


def test_a_vhdl_accelerator_is_refused_by_name_and_nothing_is_written(tmp_path):
    spec = write_spec(
        tmp_path, point_system("VHDL", "pass.vhd", "pass_point"), pass__vhd=point_vhdl()
    )
    types = message_types("ros2")
    point = "geometry_msgs/msg/Point"
    message = types.serialize(types.build(point, {"x": 1.0, "y": 2.0, "z": 3.0}), point)
    bag, out = tmp_path / "in.mcap", tmp_path / "o.mcap"
    write_bag(bag, types, {"/p": point}, [("/p", 1000, message)])
    result = run_rfc("sim", spec, "--bag", bag, "--out", out, "--backend", "myhdl")
    assert result.returncode == 1
    assert "not MyHDL (pass_point" in result.stderr
    assert "hint: use --backend ghdl" in result.stderr
    assert "Traceback" not in result.stderr
    assert not out.exists()
