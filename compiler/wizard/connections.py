"""The connections the wizard proposes: each message goes to the next block that takes its type."""

from __future__ import annotations

from rfc.messages.rosbags_adapter import MessageTypes
from rfc.wizard.model import AcceleratorAnswers, BlockAnswers, ConnectionAnswer


def propose(
    types: MessageTypes,
    accelerators: tuple[AcceleratorAnswers, ...],
    blocks: tuple[BlockAnswers, ...],
) -> tuple[ConnectionAnswer, ...]:
    """Connect every subscriber and accelerator output to the first free input of its type.

    Inputs are the accelerators' ports (in block order) and then the publishers; an output goes
    to an accelerator declared after its own block, so the proposal never loops.
    """
    by_type = {a.name: a for a in accelerators}
    inputs: list[tuple[int, str, str, str]] = []  # (block index, block, port, canonical type)
    outputs: list[tuple[int, str, str, str]] = []  # (block index, block, port, canonical type)
    for index, block in enumerate(blocks):
        if block.kind == "subscriber":
            outputs.append((index, block.name, "", types.resolve(block.message)))
        elif block.kind == "publisher":
            inputs.append((index, block.name, "", types.resolve(block.message)))
        else:
            accelerator = by_type[block.accelerator]
            several = len(accelerator.inputs) > 1
            for port in accelerator.inputs:
                name = port.name if several else ""
                inputs.append((index, block.name, name, types.resolve(port.message)))
            for port in accelerator.outputs:
                name = port.name if len(accelerator.outputs) > 1 else ""
                outputs.append((index, block.name, name, types.resolve(port.message)))
    found: list[ConnectionAnswer] = []
    for index, source, output, message in outputs:
        for entry in inputs:
            if entry[0] > index and entry[3] == message:
                inputs.remove(entry)
                found.append(ConnectionAnswer(source, entry[1], entry[2], output))
                break
    return tuple(found)
