"""rfc sim --netlist: what synthesis makes of the logic gives the bytes the RTL gives.

The same random bag goes through the RTL and through GHDL's synthesized netlist of every
generated component (structural top level kept); the output bags must be identical, and the
pass-through system's outputs must be the very bytes rosbags serialized.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.examples.multi_type.test_system import TOPICS, image, scan, twist
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
QUATERNION = "geometry_msgs/msg/Quaternion"


def replay_both(spec: Path, bag: Path, folder: Path, *options: str) -> tuple[bytes, bytes]:
    """The output bag of the RTL and of the netlist, as bytes."""
    outputs = []
    for name, extra in (("rtl", ()), ("netlist", ("--netlist",))):
        out = folder / f"{name}.mcap"
        args = ("sim", spec, "--bag", bag, "--out", out, "--json", *options, *extra)
        result = run_rfc(*args, cwd=ROOT)
        assert result.returncode == 0, result.stderr
        assert json.loads(result.stdout)["dropped"] == []
        outputs.append(out.read_bytes())
    return outputs[0], outputs[1]


def test_the_quaternion_systems_netlist_gives_the_rtls_angles(tmp_path):
    rng = np.random.default_rng(21)
    types = message_types("ros2")
    quaternions = rng.normal(size=(12, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    messages = [
        (
            "/imu/orientation",
            1500 * (i + 1),
            types.serialize(
                types.build(QUATERNION, dict(zip("xyzw", map(float, q), strict=True))), QUATERNION
            ),
        )
        for i, q in enumerate(quaternions)
    ]
    bag = tmp_path / "q.mcap"
    write_bag(bag, types, {"/imu/orientation": QUATERNION}, messages)
    spec = ROOT / "examples/quaternion_to_euler/project.yaml"
    rtl, netlist = replay_both(spec, bag, tmp_path, "--drain-cycles", "300")
    assert netlist == rtl
    assert len(list(read_bag(tmp_path / "netlist.mcap", types))) == 12


def test_strings_and_byte_sequences_of_every_length_modulo_the_bus_pass_the_netlist(tmp_path):
    rng = np.random.default_rng(5)
    types = message_types("ros2")
    makers = {"/camera/image": image, "/scan": scan, "/cmd_vel": twist}
    messages = []
    for index in range(9):  # frame ids of 0 … 8 bytes: every length modulo 8 bytes
        topic = list(makers)[index % 3]
        kind = TOPICS[topic][0]
        values = makers[topic](rng)
        values["header"]["frame_id"] = "f" * index
        messages.append(
            (topic, 1_000_000 * (index + 1), types.serialize(types.build(kind, values), kind))
        )
    bag = tmp_path / "in.mcap"
    write_bag(bag, types, {t: k for t, (k, _) in TOPICS.items()}, messages)
    rtl, netlist = replay_both(ROOT / "examples/multi_type/MultiType.yaml", bag, tmp_path)
    assert netlist == rtl
    renamed = {t: o for t, (_, o) in TOPICS.items()}
    outputs = sorted((m.topic, m.data) for m in read_bag(tmp_path / "netlist.mcap", types))
    assert outputs == sorted((renamed[t], data) for t, _, data in messages)


def test_netlist_needs_the_ghdl_backend(tmp_path):
    spec = ROOT / "examples/quaternion_to_euler/project.yaml"
    bag = tmp_path / "q.mcap"
    write_bag(bag, message_types("ros2"), {"/imu/orientation": QUATERNION}, [])
    args = ("sim", spec, "--bag", bag, "--out", tmp_path / "o.mcap", "--netlist")
    result = run_rfc(*args, "--backend", "myhdl", cwd=ROOT)
    assert result.returncode == 2
    assert "--netlist simulates VHDL netlists" in result.stderr
