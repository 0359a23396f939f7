"""Placement: which blocks run in the logic, and the converters derived where data crosses."""

from __future__ import annotations

from rfc.driver import compile_spec
from rfc.ir.text import format_ir
from rfc.passes.pipeline import MODEL_PIPELINE
from tests.runtime.support import compiled, system_copy

HW_TO_SW = ("type: MyHDL", "type: ROS-SW")


def test_crossings_get_converters_after_the_declared_ones(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml")
    infrastructure = design.infrastructure
    assert [(c.id, c.block) for c in infrastructure.subscribers] == [
        (0, "Pose_sub"),
        (1, "Pass2_in0_sub"),
    ]
    assert [(c.id, c.block) for c in infrastructure.publishers] == [
        (0, "Pose_pub"),
        (1, "Pass_out0_pub"),
    ]
    crossing_sub = infrastructure.subscribers[1].crossing
    crossing_pub = infrastructure.publishers[1].crossing
    assert (crossing_sub.hardware, crossing_sub.software) == ("Pass2.in0", ("Clear.out0",))
    assert (crossing_pub.hardware, crossing_pub.software) == ("Pass.out0", ("Clear.in0",))
    assert infrastructure.software == ("Clear",)
    links = {(str(c.source), str(c.destination)) for c in infrastructure.hardware_connections}
    assert links == {
        ("Pose_sub.out0", "Pass.in0"),
        ("Pass.out0", "Pass_out0_pub.in0"),
        ("Pass2_in0_sub.out0", "Pass2.in0"),
        ("Pass2.out0", "Pose_pub.in0"),
    }
    assert [i.publisher for i in infrastructure.scheduler.inputs] == ["Pose_pub", "Pass_out0_pub"]
    text = format_ir(design)
    assert "crossing: {hardware: Pass.out0, software: [Clear.in0]}" in text
    assert "  software:\n    - Clear\n" in text


def test_an_all_hardware_system_keeps_its_connections(tmp_path):
    # Its ROS-SW functions are no MyHDL blocks: the model only, without check-hardware.
    spec = system_copy(tmp_path, "pose_mixed.yaml", ("type: ROS-SW", "type: MyHDL"))
    design = compile_spec(spec, pipeline=MODEL_PIPELINE)
    infrastructure = design.infrastructure
    assert infrastructure.hardware_connections == design.connections
    assert infrastructure.software == ()
    assert [c.block for c in infrastructure.subscribers] == ["Pose_sub"]
    assert [c.block for c in infrastructure.publishers] == ["Pose_pub"]


def test_an_all_software_system_has_no_converters_in_the_logic(tmp_path):
    design = compiled(tmp_path, "pose_mixed.yaml", HW_TO_SW)
    infrastructure = design.infrastructure
    assert infrastructure.subscribers == infrastructure.publishers == ()
    assert infrastructure.hardware_connections == ()
    assert infrastructure.software == ("Pass", "Clear", "Pass2")
    assert infrastructure.scheduler.inputs == ()


def test_a_crossing_name_never_takes_a_block_name(tmp_path):
    design = compiled(
        tmp_path,
        "pose_mixed.yaml",
        ("name: Pose_pub, type", "name: Pass_out0_pub, type"),
        ("{name: Pose_pub}", "{name: Pass_out0_pub}"),
    )
    assert [c.block for c in design.infrastructure.publishers] == [
        "Pass_out0_pub",
        "Pass_out0_pub2",
    ]
