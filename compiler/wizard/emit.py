"""The answers written as a spec: YAML in the paper's Listing 1 form, or the Python form."""

from __future__ import annotations

import io
from typing import Any

from ruamel.yaml import YAML

from rfc.wizard.model import BlockAnswers, ConnectionAnswer, PortAnswer, SystemAnswers

_HEADER = "Written by rfc wizard; edit freely, then run rfc check on it."


def to_yaml(system: SystemAnswers) -> str:
    """Return the spec in YAML, Listing 1's spelling (``fpgaPart``, ``ROS>accelerator``...)."""
    project = system.project
    document: dict[str, Any] = {
        "project": {
            "name": project.name,
            "fpgaPart": project.fpga_part,
            "middleware": project.middleware.upper(),
            "distro": project.distro,
            "busWidth": project.bus_width,
            "clockMHz": _number(project.clock_mhz),
            "scheduler": project.scheduler,
            **({"msg_paths": list(project.msg_paths)} if project.msg_paths else {}),
        },
        "accelerators": [
            {
                "name": a.name,
                "type": a.kind,
                "sources": a.sources,
                **({"top": a.top} if a.top else {}),
                **({"reference": a.reference} if a.reference else {}),
                "interface": {"input": _ports(a.inputs), "output": _ports(a.outputs)},
            }
            for a in system.accelerators
        ],
        "blocks": [_block(b, system.connections) for b in system.blocks],
    }
    yaml = YAML()
    yaml.default_flow_style = False
    yaml.indent(mapping=2, sequence=4, offset=2)
    out = io.StringIO()
    out.write(f"# {_HEADER}\n")
    yaml.dump(document, out)
    return out.getvalue()


def _number(value: float) -> float | int:
    return int(value) if value == int(value) else value


def _ports(ports: tuple[PortAnswer, ...]) -> list[dict[str, str]]:
    return [{"name": p.name, "message": p.message} for p in ports]


def _block(block: BlockAnswers, connections: tuple[ConnectionAnswer, ...]) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": block.name}
    if block.kind == "accelerator":
        entry["type"] = block.accelerator
    else:
        entry["type"] = "ROS>accelerator" if block.kind == "subscriber" else "accelerator>ROS"
        entry["mode"] = block.kind
        entry["message"] = block.message
        entry["topic"] = block.topic
        if block.period:
            entry["period"] = int(block.period) if block.period.isdigit() else block.period
    outgoing = []
    for connection in connections:
        if connection.source == block.name:
            target: dict[str, Any] = {"name": connection.destination}
            if connection.port:
                target["port"] = connection.port
            if connection.output:
                target["from"] = connection.output
            if block.include:
                target["include"] = list(block.include)
            outgoing.append(target)
    if outgoing:
        entry["outgoing"] = outgoing
    return entry


def to_python(system: SystemAnswers) -> str:
    """Return the spec in the Python form (`rfc.Project`, `rfc.external_accelerator`)."""
    project = system.project
    lines = [f'"""{_HEADER}"""', ""]
    references = sorted({a.reference for a in system.accelerators if a.reference})
    for reference in references:
        file, _, function = reference.rpartition(":")
        module = file.rsplit("/", 1)[-1].removesuffix(".py")
        lines.append(f"from {module} import {function}")
    lines += ["", "import rfc", ""]
    for accelerator in system.accelerators:
        lines += [
            f"{accelerator.name} = rfc.external_accelerator(",
            f"    {accelerator.name!r},",
            f"    kind={accelerator.kind!r},",
            f"    sources={accelerator.sources!r},",
            f"    inputs={_port_dict(accelerator.inputs)},",
            f"    outputs={_port_dict(accelerator.outputs)},",
        ]
        if accelerator.top:
            lines.append(f"    top={accelerator.top!r},")
        if accelerator.reference:
            lines.append(f"    reference={accelerator.reference.rpartition(':')[2]},")
        lines += [")", ""]
    lines += [
        "project = rfc.Project(",
        f"    {project.name!r},",
        f"    fpga_part={project.fpga_part!r},",
        f"    middleware={project.middleware.upper()!r},",
        f"    distro={project.distro!r},",
        f"    bus_width={project.bus_width},",
        f"    clock_mhz={_number(project.clock_mhz)},",
        f"    scheduler={project.scheduler!r},",
    ]
    if project.msg_paths:
        lines.append(f"    msg_paths={list(project.msg_paths)!r},")
    lines.append(")")
    handles = {}
    for index, block in enumerate(system.blocks):
        handle = f"block{index}"
        handles[block.name] = handle
        if block.kind == "accelerator":
            lines.append(f"{handle} = project.accelerator({block.name!r}, {block.accelerator})")
            continue
        timing = f", period={block.period!r}" if block.period else ""
        if block.period.isdigit():
            timing = f", period={block.period}"
        lines.append(
            f"{handle} = project.{block.kind}({block.name!r}, {block.message!r}, "
            f"topic={block.topic!r}{timing})"
        )
    lines.append("")
    includes = {b.name: b.include for b in system.blocks if b.include}
    for connection in system.connections:
        source = handles[connection.source]
        if connection.output:
            source += f"[{connection.output!r}]"
        if connection.source in includes:
            source += ".include(" + ", ".join(map(repr, includes[connection.source])) + ")"
        destination = handles[connection.destination]
        if connection.port:
            destination += f"[{connection.port!r}]"
        lines.append(f"{source} >> {destination}")
    return "\n".join(lines) + "\n"


def _port_dict(ports: tuple[PortAnswer, ...]) -> str:
    return "{" + ", ".join(f"{p.name!r}: {p.message!r}" for p in ports) + "}"
