"""HLS accelerators C-simulated in `rfc sim`: every field kind, Franka's state, and the errors."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from rfc.driver import compile_spec
from rfc.errors import RfcError
from rfc.messages.codec import default_values
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from rfc.messages.values import values_to_message
from rfc.passes.pipeline import PIPELINE
from rfc.sim.hls_csim import HlsOnProcessor, attach_c_simulations
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]
SYSTEM = ROOT / "tests" / "runtime" / "systems" / "hls"
KINDS = "rfc_kinds/msg/Kinds"
BAG_SUFFIX = {"ROS": ".bag", "ROS2": ".mcap"}
MIDDLEWARE = {"ROS": "ros1", "ROS2": "ros2"}
FRANKA = "franka_msgs/msg/FrankaState"
FRANKA_ARRAYS = {"q": 7, "q_d": 7, "O_T_EE": 16, "O_T_EE_d": 16, "F_T_EE": 16}


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))


def copy_system(directory: Path, middleware: str = "ROS2", source: str | None = None) -> Path:
    shutil.copytree(SYSTEM, directory, dirs_exist_ok=True)
    spec = directory / "copy.yaml"
    spec.write_text(spec.read_text().replace("middleware: ROS2", f"middleware: {middleware}"))
    if source is not None:
        (directory / "copy.cpp").write_text(source)
    return spec


def kinds_messages(types, count: int, seed: int = 5) -> list[bytes]:
    """Kinds messages with random values, strings and sequences of growing length."""
    rng = np.random.default_rng(seed)
    messages = []
    for index in range(count):
        tree = {
            "flag": bool(index % 2),
            **{f"i{b}": int(rng.integers(-(2 ** (b - 1)), 2 ** (b - 1))) for b in (8, 16, 32, 64)},
            **{f"u{b}": int(rng.integers(0, 2**b, dtype=np.uint64)) for b in (8, 16, 32, 64)},
            "f32": float(np.float32(rng.normal())),
            "f64": float(rng.normal()),
            "name": "kinds"[:index],
            "gains": rng.normal(size=3),
            "corners": [{"x": rng.normal(), "y": rng.normal(), "z": rng.normal()} for _ in "ab"],
            "samples": rng.integers(0, 2**16, size=3 * index, dtype=np.uint16),
            "cloud": [
                {"x": float(np.float32(v)), "y": -1.5, "z": 2.0} for v in rng.normal(size=index)
            ],
        }
        messages.append(types.serialize(types.build(KINDS, tree), KINDS))
    return messages


def kinds_bag(directory: Path, middleware: str, count: int = 4) -> tuple[Path, list[bytes]]:
    types = message_types(MIDDLEWARE[middleware], msg_paths=(str(directory / "msg"),))
    data = kinds_messages(types, count)
    bag = directory / f"kinds{BAG_SUFFIX[middleware]}"
    write_bag(
        bag, types, {"/kinds": KINDS}, [("/kinds", 1000 * (i + 1), d) for i, d in enumerate(data)]
    )
    return bag, data


def sim(spec: Path, bag: Path, out: Path):
    return run_rfc("sim", spec, "--bag", bag, "--out", out, "--json", cwd=spec.parent)


@pytest.mark.parametrize("middleware", ["ROS", "ROS2"])
def test_every_field_kind_goes_through_a_c_simulated_copy_unchanged(tmp_path, middleware):
    spec = copy_system(tmp_path, middleware)
    bag, sent = kinds_bag(tmp_path, middleware)
    out = tmp_path / f"copy{BAG_SUFFIX[middleware]}"
    result = sim(spec, bag, out)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["software_calls"] == {"Copy_acc": len(sent)}
    types = message_types(MIDDLEWARE[middleware], msg_paths=(str(tmp_path / "msg"),))
    assert [m.data for m in read_bag(out, types)] == sent


def test_the_harness_is_compiled_once_per_content(tmp_path):
    spec = copy_system(tmp_path)
    pipeline = (HlsOnProcessor(), *PIPELINE)
    first = attach_c_simulations(compile_spec(spec, pipeline=pipeline), tmp_path / "builds")
    program = first.accelerator("Copy").reference_function.program
    built = program.stat().st_mtime_ns
    again = attach_c_simulations(compile_spec(spec, pipeline=pipeline), tmp_path / "builds")
    assert again.accelerator("Copy").reference_function.program == program
    assert program.stat().st_mtime_ns == built
    source = tmp_path / "copy.cpp"
    source.write_text(source.read_text().replace("kout->i8 = kin.i8;", "kout->i8 = -kin.i8;"))
    changed = attach_c_simulations(compile_spec(spec, pipeline=pipeline), tmp_path / "builds")
    assert changed.accelerator("Copy").reference_function.program != program


def test_a_compile_error_names_the_source_line(tmp_path):
    broken = (SYSTEM / "copy.cpp").read_text().replace("kout->u8 = kin.u8;", "kout->u8 = kin.u9;")
    spec = copy_system(tmp_path, source=broken)
    bag, _ = kinds_bag(tmp_path, "ROS2")
    result = sim(spec, bag, tmp_path / "out.mcap")
    assert result.returncode == 1
    line = broken.splitlines().index("    kout->u8 = kin.u9;") + 1
    assert f"copy.cpp:{line}:" in result.stderr
    assert "g++ cannot compile HLS accelerator 'Copy'" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "out.mcap").exists()


def test_a_top_function_without_the_structs_is_refused_at_its_argument(tmp_path):
    source = "#include <cstdint>\nvoid Copy(double kin, double *kout) {\n  *kout = kin;\n}\n"
    spec = copy_system(tmp_path, source=source)
    with pytest.raises(RfcError) as error:
        attach_c_simulations(compile_spec(spec, pipeline=(HlsOnProcessor(), *PIPELINE)))
    assert "has 2 arguments; its messages give 8" in str(error.value)
    assert error.value.location is not None
    assert error.value.location.line == 2
    assert "void Copy(kin_t kin, hls::stream<char> &kin_name," in str(error.value)


@pytest.mark.parametrize(
    ("edit", "said"),
    [
        (
            ("kout_samples.write(kin_samples.read());", "kout_samples.write(0);"),
            "left 3 elements unread on kin_samples",
        ),
        (
            ("kout->cloud_length = kin.cloud_length;", "kout->cloud_length = 7;"),
            "wrote 0 elements on stream kout_cloud but set kout->cloud_length to 7",
        ),
    ],
)
def test_a_function_that_breaks_its_streams_stops_the_replay_with_a_sentence(tmp_path, edit, said):
    spec = copy_system(tmp_path, source=(SYSTEM / "copy.cpp").read_text().replace(*edit))
    bag, _ = kinds_bag(tmp_path, "ROS2", count=2)
    result = sim(spec, bag, tmp_path / "out.mcap")
    assert result.returncode == 1
    assert said in result.stderr
    assert "Traceback" not in result.stderr


def test_franka_state_is_taken_by_an_hls_function_with_one_struct(tmp_path):
    spec = Path(shutil.copytree(SYSTEM.parent / "franka_hls", tmp_path / "franka")) / "sums.yaml"
    spec.write_text(spec.read_text().replace("../../../../examples", str(ROOT / "examples")))
    types = message_types("ros1", msg_paths=(str(ROOT / "examples" / "franka" / "msg"),))
    layout = flatten(types, FRANKA)
    rng = np.random.default_rng(11)
    states, data = [], []
    for index in range(3):
        values = default_values(layout)
        values.update({"header.seq": index, "header.stamp.sec": 7 + index})
        values["header.frame_id"] = f"panda_link{index}"
        state = {name: rng.normal(size=size) for name, size in FRANKA_ARRAYS.items()}
        for name, array in state.items():
            values.update({f"{name}[{i}]": float(v) for i, v in enumerate(array)})
        states.append(state)
        data.append(types.serialize(values_to_message(values, layout, types), FRANKA))
    bag = tmp_path / "franka.bag"
    write_bag(
        bag,
        types,
        {"/franka_state": FRANKA},
        [("/franka_state", i + 1, d) for i, d in enumerate(data)],
    )
    out = tmp_path / "sums.bag"
    result = sim(spec, bag, out)
    assert result.returncode == 0, result.stderr
    sums = [types.deserialize(m.data, m.type_name) for m in read_bag(out, types)]
    assert len(sums) == len(states)
    for index, (state, message) in enumerate(zip(states, sums, strict=True)):
        transforms = 0.0
        for i in range(16):  # the function's order of operations, in float64
            transforms += state["O_T_EE"][i] - state["O_T_EE_d"][i] + state["F_T_EE"][i]
        point = message.point
        assert (point.x, point.y, point.z) == (sum(state["q"]), sum(state["q_d"]), transforms)
        assert message.header.frame_id == f"panda_link{index}"
        assert (message.header.seq, message.header.stamp.sec) == (index, 7 + index)
