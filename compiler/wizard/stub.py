"""Reference stubs: the Python function a ROS-SW accelerator runs, ready to be filled in."""

from __future__ import annotations

from rfc.wizard.model import AcceleratorAnswers


def reference_stub(accelerator: AcceleratorAnswers) -> str:
    """Return a module defining the accelerator's reference function.

    The function takes one rosbags message per input port, in port order (rfc's ROS-SW calling
    convention). When the first input and output carry the same type it passes the message on,
    so the system runs end to end before any code is written; otherwise it sends nothing.
    """
    function = accelerator.reference.rpartition(":")[2]
    arguments = ", ".join(p.name for p in accelerator.inputs)
    first_in, first_out = accelerator.inputs[0], accelerator.outputs[0]
    if first_in.message == first_out.message and len(accelerator.outputs) == 1:
        body = f"    return {first_in.name}"
        doc = f"Pass the {first_in.message} on unchanged (replace with the accelerator's work)."
    else:
        body = "    return None"
        doc = "Send nothing yet (return one message per output port, in port order)."
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
