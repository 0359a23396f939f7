"""One logic, three readings: RTL VHDL in GHDL = GHDL's netlist = the Verilog in Verilator.

The same random bag goes through the RTL VHDL (``--simulator ghdl``), through GHDL's
synthesized netlist of every generated component (``--netlist``, structural top level kept) and
through rfc's Verilog in Verilator (``--simulator verilator``); the output bags must be
identical, and the pass-through system's outputs must be the very bytes rosbags serialized.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from tests.examples.multi_type.test_system import TOPICS, image, scan, twist
from tests.lower.system.systems import point_system, point_vhdl, write_spec
from tests.support.cli import run_rfc
from tests.support.sim_readings import replay_readings

ROOT = Path(__file__).resolve().parents[2]
QUATERNION = "geometry_msgs/msg/Quaternion"


def replay_all(spec: Path, bag: Path, folder: Path, *options: str) -> dict[str, bytes]:
    """The output bag of each reading of the logic, as bytes."""
    outputs = replay_readings(spec, bag, folder, *options)
    return {name: out.read_bytes() for name, out in outputs.items()}


@pytest.mark.slow
@pytest.mark.parametrize("variant", ["project.yaml", "project_iterative.yaml"])
def test_the_quaternion_system_gives_the_same_angles_in_every_reading(tmp_path, variant):
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
    # the pipelined core (the example) and the small iterative one
    spec = ROOT / "examples/quaternion_to_euler" / variant
    outputs = replay_all(spec, bag, tmp_path, "--drain-cycles", "300")
    assert outputs["netlist"] == outputs["rtl"]
    assert outputs["verilog"] == outputs["rtl"]
    assert len(list(read_bag(tmp_path / "verilog.mcap", types))) == 12
    if variant != "project.yaml":
        return
    # the compiled model is cached by content: a second run does not build again
    (model,) = (tmp_path / "cache/verilator").iterdir()
    built = (model / "Vdut").stat().st_mtime_ns
    args = ("sim", spec, "--bag", bag, "--out", tmp_path / "again.mcap", "--drain-cycles", "300")
    result = run_rfc(*args, cwd=ROOT, env={"RFC_CACHE_DIR": str(tmp_path / "cache")})
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "again.mcap").read_bytes() == outputs["rtl"]  # Verilator by default
    assert [m.name for m in (tmp_path / "cache/verilator").iterdir()] == [model.name]
    assert (model / "Vdut").stat().st_mtime_ns == built


@pytest.mark.slow
def test_strings_and_byte_sequences_of_every_length_modulo_the_bus_pass_every_reading(tmp_path):
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
    outputs = replay_all(ROOT / "examples/multi_type/MultiType.yaml", bag, tmp_path)
    assert outputs["netlist"] == outputs["rtl"]
    assert outputs["verilog"] == outputs["rtl"]
    renamed = {t: o for t, (_, o) in TOPICS.items()}
    outputs = sorted((m.topic, m.data) for m in read_bag(tmp_path / "verilog.mcap", types))
    assert outputs == sorted((renamed[t], data) for t, _, data in messages)


def test_netlist_needs_the_ghdl_backend(tmp_path):
    spec = ROOT / "examples/quaternion_to_euler/project.yaml"
    bag = tmp_path / "q.mcap"
    write_bag(bag, message_types("ros2"), {"/imu/orientation": QUATERNION}, [])
    args = ("sim", spec, "--bag", bag, "--out", tmp_path / "o.mcap", "--netlist")
    result = run_rfc(*args, "--backend", "myhdl", cwd=ROOT)
    assert result.returncode == 2
    assert "--netlist simulates VHDL netlists" in result.stderr


@pytest.mark.parametrize("synthesizable", [True, False], ids=["ghdl-netlist", "stays-vhdl"])
def test_a_logic_with_a_vhdl_accelerator_is_refused_by_verilator(tmp_path, synthesizable):
    vhdl = point_vhdl()  # two drivers of out0_x: GHDL's synthesis refuses it, not without them
    if synthesizable:
        vhdl = vhdl.replace("  out0_x <= (others => '0');\n", "")
    spec = write_spec(tmp_path, point_system("VHDL", "pass.vhd", "pass_point"), pass__vhd=vhdl)
    types = message_types("ros2")
    point = "geometry_msgs/msg/Point"
    data = types.serialize(types.build(point, {"x": 1.0, "y": 2.0, "z": 3.0}), point)
    bag = tmp_path / "p.mcap"
    write_bag(bag, types, {"/p": point}, [("/p", 1000, data)])
    args = ("sim", spec, "--bag", bag, "--out", tmp_path / "o.mcap", "--simulator", "verilator")
    result = run_rfc(*args, cwd=ROOT)
    assert result.returncode == 1
    assert "this logic is not all in rfc's Verilog" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "o.mcap").exists()
