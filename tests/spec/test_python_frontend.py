"""The Python front-end: annotated MyHDL blocks, `>>` wiring, and errors at the call site."""

from __future__ import annotations

import inspect
import subprocess
import sys
from pathlib import Path

import pytest

import rfc
from rfc.driver import compile_spec
from rfc.errors import RfcError
from rfc.ir.model import AcceleratorKind
from rfc.passes.pipeline import run_pipeline
from rfc.spec.python_accelerators import AcceleratorDefinition

SYSTEMS = Path(__file__).parent / "systems"
sys.path.insert(0, str(SYSTEMS))
from quat_model import QuaternionToEuler, quat_to_euler  # noqa: E402

HERE = Path(__file__).resolve()


def line() -> int:
    """The line of the caller, to compare with recorded locations."""
    return inspect.currentframe().f_back.f_lineno


def quaternion_project(**settings):
    project = rfc.Project("P", **settings)
    sub = project.subscriber("Sub", "geometry_msgs/Quaternion")
    acc = project.accelerator("Acc", QuaternionToEuler)
    pub = project.publisher("Pub", "geometry_msgs/Point")
    return project, sub, acc, pub


def test_decorator_records_the_block_its_ports_and_reference():
    assert isinstance(QuaternionToEuler, AcceleratorDefinition)
    definition = QuaternionToEuler.definition
    assert definition.kind is AcceleratorKind.MYHDL
    assert definition.top == "QuaternionToEuler"
    assert definition.sources == ((SYSTEMS / "quat_model.py").resolve(),)
    assert [(p.name, p.message) for p in definition.ports] == [
        ("q", "geometry_msgs/Quaternion"),
        ("euler", "geometry_msgs/Point"),
    ]
    assert definition.reference.name == "quat_to_euler"
    assert definition.reference_function is quat_to_euler


def test_decorated_block_still_instantiates_as_a_myhdl_block():
    from types import SimpleNamespace

    from myhdl import ResetSignal, Signal, intbv

    clk, reset = Signal(bool(0)), ResetSignal(0, active=1, isasync=False)
    q, euler = (SimpleNamespace(x=Signal(intbv(0)[64:])) for _ in range(2))
    instance = QuaternionToEuler(clk, reset, q, euler)
    assert type(instance).__name__ == "_Block"


def test_chained_wiring_builds_both_connections():
    project, sub, acc, pub = quaternion_project()
    assert (sub >> acc["q"] >> pub).name == "Pub"
    design = run_pipeline(project.design())
    assert [(str(c.source), str(c.destination)) for c in design.connections] == [
        ("Sub.out0", "Acc.q"),
        ("Acc.euler", "Pub.in0"),
    ]


def test_selections_on_either_side_of_the_arrow():
    project, sub, acc, pub = quaternion_project()
    sub.include("x", "y") >> acc
    acc >> pub
    connect_location = line() - 2
    design = project.design()
    first = design.connections[0]
    assert first.carries.include == ("x", "y")
    assert (Path(first.location.file).resolve(), first.location.line) == (HERE, connect_location)
    assert first.location.column == 5
    expanded = run_pipeline(design).connections[0]
    assert expanded.fields == ("x", "y")


def test_include_and_exclude_chain_on_one_source():
    project, sub, acc, pub = quaternion_project()
    sub.include("x", "y").include("z").exclude("z") >> acc
    acc >> pub
    first = project.design().connections[0]
    assert (first.carries.include, first.carries.exclude) == (("x", "y", "z"), ("z",))
    assert run_pipeline(project.design()).connections[0].fields == ("x", "y")


def test_connect_is_the_long_form_of_the_arrow():
    project, sub, acc, pub = quaternion_project()
    project.connect(sub, acc, exclude=["w"])
    project.connect(acc, pub)
    assert run_pipeline(project.design()).connections[0].fields == ("x", "y", "z")


def test_connections_are_grouped_by_source_block_like_yaml():
    project, sub, acc, pub = quaternion_project()
    acc >> pub
    sub >> acc
    assert [c.source.block for c in project.design().connections] == ["Sub", "Acc"]


def test_pass_errors_point_at_the_users_line():
    project, sub, _, pub = quaternion_project()
    sub >> pub
    mismatch = line() - 1
    with pytest.raises(RfcError) as caught:
        run_pipeline(project.design())
    assert caught.value.location.line == mismatch
    assert Path(caught.value.location.file).resolve() == HERE


def test_argument_errors_are_raised_at_the_call():
    with pytest.raises(RfcError) as caught:
        rfc.Project("P", bus_width=12)
    assert caught.value.location.line == line() - 1
    project = rfc.Project("P")
    with pytest.raises(RfcError, match="unknown argument 'perod'"):
        project.publisher("Pub", "geometry_msgs/Point", perod=10)
    with pytest.raises(RfcError, match=r"needs a type made with @rfc\.accelerator"):
        project.accelerator("Acc", quat_to_euler)
    with pytest.raises(RfcError, match="'>>' needs a block or a port on its right"):
        project.subscriber("Sub", "geometry_msgs/Quaternion") >> "Pub"


def test_external_accelerator_checks_its_sources_and_has_no_block_to_call():
    definition = rfc.external_accelerator(
        "Ext", kind="hls", sources="catalogue/accel.cpp", inputs=[], outputs=[]
    )
    assert definition.definition.kind is AcceleratorKind.HLS
    assert definition.definition.sources == (SYSTEMS.parent / "catalogue" / "accel.cpp",)
    with pytest.raises(RfcError, match="HLS accelerator 'Ext' has no Python block to call"):
        definition()
    with pytest.raises(RfcError, match=r"whose sources end in \.vhd, \.vhdl"):
        rfc.external_accelerator("Ext", kind="VHDL", sources=HERE.name, inputs=[], outputs=[])


def test_python_spec_file_is_found_and_compiled():
    design = compile_spec(SYSTEMS / "quat_myhdl.py")
    assert design.project.scheduler == "LOEDF"
    assert design.accelerators[0].block_function is QuaternionToEuler.definition.block_function


def test_import_rfc_stays_light():
    heavy = "('rosbags', 'myhdl', 'numpy')"
    code = f"import sys, rfc; print([m for m in {heavy} if m in sys.modules])"
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "[]"
