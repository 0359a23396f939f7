"""Names the generated logic takes for itself, which the spec's names must leave free.

The lowering names entities after the project (``<project>_pl``, ``<project>_manager``), the
converters (``<block>_subscriber``, ``<block>_publisher``, crossings ``<block>_<port>_sub``…),
HLS adapters (``<type>_ap_ctrl``) and MyHDL's package (``pck_myhdl_…``), each in a file of that
name; an accelerator type of the same name would overwrite one. MyHDL elaborates an entity as
a Python function of the entity's name, so a MyHDL type's lowered name is no Python keyword
(``Class``, ``Def``). In the top level, blocks are
instance labels beside the clock, reset and DMA stream ports, the manager, the DMA's header
tap and the guards, gates, slices, forks and marks named after the block they serve; in an
accelerator's entity, ports sit beside the clock, reset and HLS handshake.
"""

from __future__ import annotations

import keyword

from rfc.errors import RfcError
from rfc.ir.model import AcceleratorKind, BlockKind, Design
from rfc.passes.names import snake_identifier

#: Signal and instance names of the generated top level and accelerator entities.
RESERVED_SIGNALS = frozenset(
    {
        "clk",
        "rst",
        "aclk",
        "aresetn",
        "ap_clk",
        "ap_rst",
        "ap_start",
        "ap_done",
        "ap_idle",
        "ap_ready",
        "manager",
        "chunk_tap",
    }
)
#: Prefixes of the top level's DMA stream ports.
RESERVED_PREFIXES = ("s_axis_mm2s", "m_axis_s2mm")
#: Endings of generated entities whose stem is derived, not written in the spec.
RESERVED_SUFFIXES = ("_ap_ctrl", "_sub_subscriber", "_pub_publisher")
#: Cells the lowering places beside a block: ``<label><ending>`` exactly…
CELL_ENDINGS = {"_guard": "frame guard", "_drop_gate": "drop gate"}
#: …or ``<label>_<port or stream><ending>``.
CELL_INFIX_ENDINGS = {"_slice": "register slice", "_fork": "fork", "_marks": "stream marks"}


def check_generated_names(design: Design) -> None:
    """Raise at the first spec name that a generated entity, port or instance already takes."""
    for block in design.blocks:
        label = snake_identifier(block.name)
        if label in RESERVED_SIGNALS or label.startswith(RESERVED_PREFIXES):
            raise RfcError(
                f"block '{block.name}' would be instance '{label}' of the generated top level, "
                "whose clock, reset, DMA ports, manager or DMA header tap already take that name",
                location=block.at("name"),
                hint=f"rename the block, e.g. '{block.name}_0'",
            )
    _check_cell_labels(design)
    for accelerator in design.accelerators:
        for port in accelerator.ports:
            if port.name.lower() in RESERVED_SIGNALS:
                raise RfcError(
                    f"port '{port.name}' of accelerator '{accelerator.name}' is a signal every "
                    "generated accelerator entity has (clock, reset or HLS handshake)",
                    location=port.at("name"),
                    hint=f"rename the port, e.g. '{port.name}_0'",
                )
    entities = _generated_entities(design)
    for accelerator in design.accelerators:
        name = accelerator.name.lower()
        hint = f"rename the type, e.g. '{accelerator.name}_0'"
        if accelerator.kind is AcceleratorKind.MYHDL and keyword.iskeyword(name):
            raise RfcError(
                f"MyHDL accelerator type '{accelerator.name}' would be elaborated as a Python "
                f"function '{name}', which is a Python keyword",
                location=accelerator.at("name"),
                hint=hint,
            )
        what = entities.get(name)
        if what is None and name.endswith(RESERVED_SUFFIXES):
            what = "a generated adapter or converter (the ending is reserved)"
        if what is None and name.startswith("pck_myhdl"):
            what = "MyHDL's generated package"
        if what is not None:
            raise RfcError(
                f"accelerator type '{accelerator.name}' would be entity '{name}' (hw/{name}.vhd), "
                f"the name of {what}",
                location=accelerator.at("name"),
                hint=hint,
            )


def _check_cell_labels(design: Design) -> None:
    """Raise when a block's label is one the lowering gives a cell it places beside another block.

    Guards, drop gates, slices, forks and stream marks are named ``<label>_…<ending>`` after the
    block they serve, so a block called ``cam_guard`` beside a block ``cam`` would be two cells.
    """
    labels = {snake_identifier(block.name): block for block in design.blocks}
    for label, block in labels.items():
        for stem, owner in labels.items():
            if owner is block:
                continue
            what = next((w for e, w in CELL_ENDINGS.items() if label == f"{stem}{e}"), None)
            what = what or next(
                (
                    w
                    for e, w in CELL_INFIX_ENDINGS.items()
                    if label.startswith(f"{stem}_") and label.endswith(e)
                ),
                None,
            )
            if what is not None:
                raise RfcError(
                    f"block '{block.name}' would be instance '{label}', a name the generated top "
                    f"level may give the {what} it places beside block '{owner.name}'",
                    location=block.at("name"),
                    hint=f"rename the block, e.g. '{block.name}_0'",
                )


def _generated_entities(design: Design) -> dict[str, str]:
    """Lower-case entity names the lowering generates, each with what it is."""
    project = snake_identifier(design.project.name)
    entities = {
        f"{project}_pl": "the top level of the logic",
        f"{project}_manager": "the manager",
    }
    for block in design.blocks:
        if block.kind in (BlockKind.SUBSCRIBER, BlockKind.PUBLISHER):
            entities[f"{snake_identifier(block.name)}_{block.kind.value}"] = (
                f"the {block.kind.value} converter of block '{block.name}'"
            )
    for accelerator in design.accelerators:
        if accelerator.kind is AcceleratorKind.HLS:
            entities[f"{accelerator.name.lower()}_ap_ctrl"] = (
                f"the adapter of HLS accelerator '{accelerator.name}'"
            )
    return entities
