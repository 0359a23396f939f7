"""The YAML front-end: Listing 1 as printed, the extensions of docs/spec.md, and locations."""

from __future__ import annotations

from pathlib import Path

import pytest

from rfc.errors import RfcError
from rfc.ir.model import AcceleratorKind, BlockKind, Direction, Stage
from rfc.messages.rosbags_adapter import Middleware
from rfc.spec import load_spec
from rfc.spec.yaml_frontend import load_yaml_spec

ROOT = Path(__file__).resolve().parents[2]
LISTING_1 = ROOT / "examples" / "rotation_converter" / "RotationConverterNode.yaml"


def write(tmp_path, text, name="spec.yaml"):
    (tmp_path / "accel.cpp").write_text("// accelerator\n")
    path = tmp_path / name
    path.write_text(text)
    return path


QUATERNION_SYSTEM = """\
project:
  name: P
{project}
accelerators:
  - name: Q2E
    type: HLS
    sources: ./accel.cpp
    interface:
      input: [{{message: geometry_msgs/Quaternion}}]
      output: [{{message: geometry_msgs/Point}}]
blocks:
  - name: Sub
    type: ROS>accelerator
    message: geometry_msgs/Quaternion
    outgoing: [{{name: Acc}}]
  - name: Acc
    type: Q2E
    outgoing: [{{name: Pub}}]
  - name: Pub
    type: accelerator>ROS
    message: geometry_msgs/Point
{publisher}
"""


def system(tmp_path, project="", publisher=""):
    return load_spec(
        write(tmp_path, QUATERNION_SYSTEM.format(project=project, publisher=publisher))
    )


def test_listing_1_is_the_papers_33_lines():
    lines = LISTING_1.read_text().splitlines()
    assert len(lines) == 33
    assert lines[0] == "project:"
    assert lines[17] == "  - name: Quaternion_sub # converter"
    assert lines[32] == "    message: geometry_msgs/Point"


def test_listing_1_reads_as_printed():
    design = load_spec(LISTING_1)
    assert design.stage is Stage.PARSED
    project = design.project
    assert (project.name, project.fpga_part, project.fpga_family) == (
        "RotationConverterNode",
        "xc7z020clg400-1",
        "zynq",
    )
    # `middleware: ROS` on the blocks and ports is ROS 1, as in the paper.
    assert project.middleware is Middleware.ROS1
    assert project.distro == "noetic"
    (accelerator,) = design.accelerators
    assert accelerator.kind is AcceleratorKind.HLS
    assert accelerator.sources == (LISTING_1.parent / "QuaternionToEulerConverter.cpp",)
    assert [(p.name, p.direction, p.message) for p in accelerator.ports] == [
        ("in0", Direction.IN, "geometry_msgs/Quaternion"),
        ("out0", Direction.OUT, "geometry_msgs/Point"),
    ]
    assert [(b.name, b.kind) for b in design.blocks] == [
        ("Quaternion_sub", BlockKind.SUBSCRIBER),
        ("QuatToEuler_acc", BlockKind.ACCELERATOR),
        ("Euler_pub", BlockKind.PUBLISHER),
    ]
    assert [(str(c.source), str(c.destination)) for c in design.connections] == [
        ("Quaternion_sub", "QuatToEuler_acc"),
        ("QuatToEuler_acc", "Euler_pub"),
    ]


def test_every_element_knows_its_line_and_column():
    design = load_yaml_spec(LISTING_1, "listing1.yaml")
    subscriber = design.block("Quaternion_sub")
    assert str(subscriber.location) == "listing1.yaml:18:5"
    assert str(subscriber.at("message")) == "listing1.yaml:22:14"
    assert str(design.accelerators[0].inputs[0].at("message")) == "listing1.yaml:12:20"
    first = design.connections[0]
    assert str(first.location) == "listing1.yaml:24:9"
    assert str(first.destination.location) == "listing1.yaml:24:15"


def test_defaults_are_made_explicit(tmp_path):
    project = system(tmp_path).project
    assert project.middleware is Middleware.ROS2
    assert (project.distro, project.bus_width, project.clock_mhz) == ("humble", 64, 100.0)
    assert project.scheduler == "auto"
    assert system(tmp_path).block("Pub").topic == "/Pub"


@pytest.mark.parametrize(
    ("written", "clock", "cycles"),
    [
        ("1000", 100, 1000),
        ("10 us", 100, 1000),
        ("1.5ms", 100, 150000),
        ("33 ms", 250, 8250000),
        ("15 ns", 100, 2),
    ],
)
def test_durations_become_clock_cycles(tmp_path, written, clock, cycles):
    design = system(tmp_path, f"  clockMHz: {clock}", f"    period: {written}")
    assert design.block("Pub").period == cycles


@pytest.mark.parametrize(
    ("written", "algorithm"), [("lru", "LRU"), ("{algorithm: loedf}", "LOEDF"), ("auto", "auto")]
)
def test_scheduler_as_name_or_mapping(tmp_path, written, algorithm):
    assert system(tmp_path, f"  scheduler: {written}").project.scheduler == algorithm


def test_converter_type_tolerates_spaces_around_the_arrow(tmp_path):
    text = QUATERNION_SYSTEM.format(project="", publisher="").replace(
        "type: ROS>accelerator", "type: ROS > accelerator"
    )
    assert load_spec(write(tmp_path, text)).block("Sub").kind is BlockKind.SUBSCRIBER


def test_user_message_directories_resolve_against_the_spec(tmp_path, examples_dir):
    (tmp_path / "proj").mkdir()
    spec = write(
        tmp_path / "proj",
        f"""\
project:
  name: Franka
  middleware: ROS
  msg_paths: [{examples_dir / "franka" / "msg"}]
accelerators:
  - name: Kinematics
    type: VHDL
    sources: ./kin.vhd
    interface:
      input: [{{name: state, message: franka_msgs/FrankaState, include: [q]}}]
      output: [{{name: pose, message: geometry_msgs/Pose}}]
blocks:
  - {{name: State_sub, type: ROS>accelerator, message: franka_msgs/FrankaState,
     outgoing: [{{name: Kin_acc, include: [q, dq]}}]}}
  - {{name: Kin_acc, type: Kinematics, outgoing: [{{name: Pose_pub}}]}}
  - {{name: Pose_pub, type: accelerator>ROS, message: geometry_msgs/Pose}}
""",
    )
    (tmp_path / "proj" / "kin.vhd").write_text("-- kinematics\n")
    from rfc.driver import compile_spec
    from rfc.passes.pipeline import MODEL_PIPELINE

    design = compile_spec(spec, pipeline=MODEL_PIPELINE)  # kin.vhd is no entity: the model only
    (to_accelerator, _) = design.connections
    # the connection carries q and dq; the accelerator's input needs only q
    assert to_accelerator.fields == tuple(f"q[{i}]" for i in range(7))


def test_relative_msg_path_is_relative_to_the_spec(tmp_path):
    (tmp_path / "msgs" / "my_msgs" / "msg").mkdir(parents=True)
    (tmp_path / "msgs" / "my_msgs" / "msg" / "Tick.msg").write_text("uint32 count\n")
    design = system(tmp_path, "  msg_paths: ./msgs")
    assert design.project.msg_paths == (tmp_path / "msgs",)


def test_error_location_uses_the_name_given(tmp_path):
    path = write(tmp_path, "project: {name: P}\nblocks: {}\n")
    with pytest.raises(RfcError) as caught:
        load_yaml_spec(path, "my/spec.yaml")
    assert str(caught.value.location) == "my/spec.yaml:2:9"
    assert "'blocks' of the spec must be a list, not a mapping" in caught.value.message


def test_an_unresolved_user_definition_blocks_only_the_specs_that_use_it(tmp_path):
    (tmp_path / "msgs" / "my_msgs" / "msg").mkdir(parents=True)
    (tmp_path / "msgs" / "my_msgs" / "msg" / "Tick.msg").write_text("other_msgs/Thing thing\n")
    design = system(tmp_path, "  msg_paths: [./msgs]")
    from rfc.passes.pipeline import MODEL_PIPELINE, run_pipeline

    # the quaternion system does not use my_msgs/Tick (its HLS source is a stub: model passes)
    run_pipeline(design, MODEL_PIPELINE)
    (tmp_path / "uses").mkdir()
    spec = write(
        tmp_path / "uses",
        QUATERNION_SYSTEM.format(project="  msg_paths: [../msgs]", publisher="").replace(
            "geometry_msgs/Point", "my_msgs/Tick"
        ),
    )
    with pytest.raises(RfcError) as caught:
        run_pipeline(load_spec(spec), MODEL_PIPELINE)
    assert "has type 'other_msgs/msg/Thing', which no definition provides" in caught.value.message
    assert "--msg-path" in str(caught.value)


@pytest.mark.parametrize(
    ("written", "kind", "source"),
    [
        ("HLS", AcceleratorKind.HLS, "accel.cpp"),
        ("vhdl", AcceleratorKind.VHDL, "accel.vhd"),
        ("MyHDL", AcceleratorKind.MYHDL, "accel.py"),
        ("ROS-SW", AcceleratorKind.ROS_SW, "accel.py"),
    ],
)
def test_every_accelerator_kind(tmp_path, written, kind, source):
    (tmp_path / source).write_text("# source\n")
    text = QUATERNION_SYSTEM.format(project="", publisher="")
    text = text.replace("type: HLS", f"type: {written}").replace("./accel.cpp", f"./{source}")
    (accelerator,) = load_spec(write(tmp_path, text)).accelerators
    assert accelerator.kind is kind
    assert accelerator.top == ("Q2E" if kind is AcceleratorKind.MYHDL else None)
