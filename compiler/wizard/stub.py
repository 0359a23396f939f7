"""Reference stubs: the Python function a ROS-SW accelerator runs, ready to be filled in."""

from __future__ import annotations

from rfc.wizard.model import AcceleratorAnswers


def passes_through(accelerator: AcceleratorAnswers) -> bool:
    """Whether the accelerator runs in software and could pass its one input on as its output."""
    return (
        accelerator.kind == "ROS-SW"
        and bool(accelerator.reference)
        and len(accelerator.inputs) == len(accelerator.outputs) == 1
        and accelerator.inputs[0].message == accelerator.outputs[0].message
    )


def reference_stub(accelerator: AcceleratorAnswers) -> str:
    """Return a module whose reference function passes the message on (see `passes_through`).

    The function takes one rosbags message per input port (rfc's ROS-SW calling convention), so
    the system runs end to end before any code is written.
    """
    function = accelerator.reference.rpartition(":")[2]
    arguments = ", ".join(p.name for p in accelerator.inputs)
    first_in = accelerator.inputs[0]
    body = f"    return {first_in.name}"
    doc = f"Pass the {first_in.message} on unchanged (replace with the accelerator's work)."
    ports = "\n".join(
        f"    {p.name}: {p.message}" for p in (*accelerator.inputs, *accelerator.outputs)
    )
    return (
        f'"""Reference model of accelerator {accelerator.name} ({accelerator.kind}).\n\n'
        f"Ports:\n{ports}\n"
        '"""\n\n\n'
        f"def {function}({arguments}):\n"
        f'    """{doc}"""\n'
        f"{body}\n"
    )
