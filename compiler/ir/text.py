"""The stable text form of a design: a YAML document, the same at every stage.

After derive-infrastructure this document is the *holistic model* — the paper's template
configuration, with everything explicit — that ``rfc build --emit-ir`` writes; after any other
pass it is what ``--dump-ir-after`` prints and what golden tests compare. Paths are relative
to the spec's directory, and source locations are left out unless asked for, so that the YAML
and the Python form of one system print the same text.
"""

from __future__ import annotations

import os
from dataclasses import asdict
from pathlib import Path
from typing import Any

from rfc.errors import SourceLocation
from rfc.ir.fields import selected_paths
from rfc.ir.infrastructure import Converter, Infrastructure
from rfc.ir.model import (
    AcceleratorType,
    Block,
    BlockKind,
    Connection,
    Design,
    FieldSelection,
    FunctionRef,
    Port,
)
from rfc.ir.yaml_text import Flow, dump_yaml
from rfc.messages.layout import Layout, LayoutField

#: Version of the text form; bump it when a key changes meaning.
FORMAT_VERSION = 1


def format_ir(design: Design, *, locations: bool = False) -> str:
    """Render the design as YAML text (see `to_document`)."""
    return dump_yaml(to_document(design, locations=locations))


def to_document(design: Design, *, locations: bool = False) -> dict[str, Any]:
    """The design as nested dicts and lists, every attribute explicit.

    Args:
        design: The design, at any stage.
        locations: Add an ``at: file:line:col`` entry to every node.
    """
    return _Writer(design.project.spec_dir, locations).design(design)


class _Writer:
    def __init__(self, base: Path, locations: bool) -> None:
        self.base = base
        self.locations = locations

    def _at(self, location: SourceLocation) -> dict[str, str]:
        return {"at": str(location)} if self.locations else {}

    def _path(self, path: Path) -> str:
        return Path(os.path.relpath(path, self.base)).as_posix()

    def _function(self, ref: FunctionRef | None) -> str | None:
        return None if ref is None else f"{self._path(ref.file)}:{ref.name}"

    def design(self, design: Design) -> dict[str, Any]:
        project = design.project
        document: dict[str, Any] = {
            "rfc_ir": FORMAT_VERSION,
            "stage": design.stage.name.lower(),
            "project": {
                "name": project.name,
                "fpga_part": project.fpga_part,
                "fpga_family": project.fpga_family,
                "middleware": project.middleware.value,
                "distro": project.distro,
                "bus_width": project.bus_width,
                "clock_mhz": project.clock_mhz,
                "scheduler": project.scheduler,
                "msg_paths": [self._path(p) for p in project.msg_paths],
                "maxima": {
                    "string": project.maxima.string,
                    "sequence": project.maxima.sequence,
                    "frame": project.maxima.frame,
                    "fields": dict(project.maxima.fields),
                },
                **self._at(project.location),
            },
            "accelerators": [self.accelerator(t) for t in design.accelerators],
            "blocks": [self.block(b) for b in design.blocks],
            "connections": [self.connection(c) for c in design.connections],
        }
        if design.infrastructure is not None:
            document["infrastructure"] = self.infrastructure(design.infrastructure)
        return document

    def accelerator(self, accelerator: AcceleratorType) -> dict[str, Any]:
        return {
            "name": accelerator.name,
            "kind": accelerator.kind.value,
            "sources": [self._path(p) for p in accelerator.sources],
            "top": accelerator.top,
            "reference": self._function(accelerator.reference),
            "inputs": [self.port(p) for p in accelerator.inputs],
            "outputs": [self.port(p) for p in accelerator.outputs],
            **self._at(accelerator.location),
        }

    def port(self, port: Port) -> dict[str, Any]:
        entry: dict[str, Any] = {
            "name": port.name,
            "direction": port.direction.value,
            "message": port.message,
        }
        if port.needs:
            entry["needs"] = self.selection(port.needs)
        entry.update(self._at(port.location))
        if port.layout is not None:
            entry["fields"] = layout_rows(port.layout)
        return entry

    def block(self, block: Block) -> dict[str, Any]:
        entry: dict[str, Any] = {"name": block.name, "kind": block.kind.value}
        if block.kind is BlockKind.ACCELERATOR:
            entry["type"] = block.accelerator
        else:
            entry.update(
                message=block.message,
                topic=block.topic,
                period=block.period,
                deadline=block.deadline,
                max_bytes=block.max_bytes,
            )
        entry.update(self._at(block.location))
        entry["ports"] = [self.port(p) for p in block.ports]
        return entry

    def connection(self, connection: Connection) -> dict[str, Any]:
        return {
            "from": str(connection.source),
            "to": str(connection.destination),
            "message": connection.message,
            **self.selection(connection.carries),
            "fields": None if connection.fields is None else list(connection.fields),
            **self._at(connection.location),
        }

    def selection(self, selection: FieldSelection) -> dict[str, Any]:
        return {"include": list(selection.include), "exclude": list(selection.exclude)}

    def infrastructure(self, infrastructure: Infrastructure) -> dict[str, Any]:
        document = {
            "subscribers": [self.converter(c) for c in infrastructure.subscribers],
            "publishers": [self.converter(c) for c in infrastructure.publishers],
            "dma": [
                {
                    "name": channel.name,
                    "direction": channel.direction.value,
                    "width": channel.width,
                    "converters": list(channel.converters),
                }
                for channel in infrastructure.dma
            ],
            "scheduler": {
                "algorithm": infrastructure.scheduler.algorithm,
                "inputs": [Flow(asdict(i)) for i in infrastructure.scheduler.inputs],
            },
            "buffers": [Flow(asdict(b)) for b in infrastructure.buffers],
        }
        if infrastructure.software:
            document["software"] = list(infrastructure.software)
        return document

    def converter(self, converter: Converter) -> dict[str, Any]:
        entry = {
            "id": converter.id,
            "block": converter.block,
            "topic": converter.topic,
            "message": converter.message,
            "bus_width": converter.bus_width,
            "frame_bytes": converter.frame_bytes,
            "max_frame_bytes": converter.max_frame_bytes,
            "frame_length_circuit": converter.needs_frame_length,
            "length_fields": list(converter.length_fields),
            "period": converter.period,
            "deadline": converter.deadline,
            "fields": list(selected_paths(converter.layout)),
        }
        if converter.crossing is not None:
            entry["crossing"] = Flow(
                hardware=converter.crossing.hardware, software=list(converter.crossing.software)
            )
        return entry


def layout_rows(layout: Layout) -> list[Flow]:
    """One row per leaf: path, ROS type, bits, frame offset (null: dynamic), selected."""
    return [_row(field) for field in layout.fields]


def _row(field: LayoutField) -> Flow:
    row = Flow(
        path=field.path,
        type=field.ros_type,
        bits=field.bits,
        offset=field.offset,
        selected=field.selected,
    )
    if field.element is not None:
        row["element"] = layout_rows(field.element)
    return row
