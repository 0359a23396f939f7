"""derive-infrastructure: the parts of the system the spec leaves implicit (paper §3).

From the checked, flattened graph it derives which blocks run in the logic and which on the
processor (`rfc.passes.placement`), the converters with their wire-protocol ids and frame sizes
(crossing converters included), the two DMA channels, which publishers need a frame-length
circuit and which fields feed it, the buffers needed while lengths are unknown, and the
scheduler's inputs with their timing. See `rfc.ir.infrastructure` for the contract.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.errors import RfcError, located
from rfc.ir.infrastructure import (
    CHUNK_HEADER_BYTES,
    Buffer,
    Converter,
    DmaChannel,
    DmaDirection,
    Infrastructure,
    Scheduler,
    SchedulerInput,
)
from rfc.ir.model import Block, BlockKind, Design, Stage
from rfc.lib.schedulers.spec import DEFAULT_IDLE, MAX_INPUTS, check_inputs, check_timing
from rfc.messages.layout import FieldKind, Layout, LayoutField
from rfc.messages.limits import Limits
from rfc.passes.frame_size import default_frame_bytes, frame_bound
from rfc.passes.maxima import check_maxima
from rfc.passes.placement import CrossingConverter, place


@dataclass(frozen=True)
class DeriveInfrastructure:
    """Derive converters, DMA channels, frame-length circuits, buffers and scheduler inputs."""

    name: ClassVar[str] = "derive-infrastructure"

    def apply(self, design: Design) -> Design:
        """Return the design at stage DERIVED, its `infrastructure` filled in."""
        width, maxima = design.project.bus_width, design.project.maxima
        placement = place(design)
        subscribers, publishers = (
            tuple(
                [
                    _converter(i, block, _converter_layout(block), width, maxima)
                    for i, block in enumerate(declared)
                ]
                + [
                    _crossing_converter(len(declared) + i, crossing, width, maxima)
                    for i, crossing in enumerate(crossings)
                ]
            )
            for declared, crossings in (
                (placement.subscribers, placement.crossing_subscribers),
                (placement.publishers, placement.crossing_publishers),
            )
        )
        check_maxima(design, (*subscribers, *publishers))
        buffers = tuple(
            Buffer(converter.block, field.path, converter.max_frame_bytes)
            for converter in publishers
            for field in converter.layout.fields
            if field.selected and _length_known_late(field)
        )
        infrastructure = Infrastructure(
            subscribers=subscribers,
            publishers=publishers,
            dma=(
                DmaChannel(DmaDirection.PS_TO_PL, width, tuple(c.block for c in subscribers)),
                DmaChannel(DmaDirection.PL_TO_PS, width, tuple(c.block for c in publishers)),
            ),
            scheduler=_scheduler(design, publishers),
            buffers=buffers,
            hardware_connections=placement.hardware_connections,
            software=placement.software,
        )
        return replace(design, infrastructure=infrastructure, stage=Stage.DERIVED)


def _converter_layout(block: Block) -> Layout:
    (port,) = block.ports
    assert port.layout is not None
    return port.layout


def _max_frame_bytes(block: Block, layout: Layout, exact: int | None, maxima: Limits) -> int:
    if exact is not None:
        if block.max_bytes is not None and block.max_bytes < exact:
            raise RfcError(
                f"maxBytes of {block.kind.value} '{block.name}' is {block.max_bytes}, but "
                f"every {layout.display_name} frame is {exact} bytes",
                location=block.at("maxBytes"),
            )
        return exact
    if block.max_bytes is not None:
        return block.max_bytes
    bound = frame_bound(layout, maxima)
    assert bound is not None, "with maxima every frame has a bound"
    return bound


def _timing(block: Block) -> tuple[int | None, int | None]:
    deadline = block.deadline if block.deadline is not None else block.period
    if block.period is not None and deadline is not None and deadline > block.period:
        raise RfcError(
            f"deadline of {block.kind.value} '{block.name}' ({deadline} cycles) exceeds its "
            f"period ({block.period} cycles); rfc schedules constrained deadlines (D ≤ T + F)",
            location=block.at("deadline"),
        )
    return block.period, deadline


def _block_of(design: Design, converter: Converter) -> Block | None:
    return None if converter.crossing is not None else design.block(converter.block)


def _crossing_converter(
    index: int, crossing: CrossingConverter, width: int, maxima: Limits
) -> Converter:
    """A converter at a crossing: named after its hardware port, with no topic or timing."""
    assert crossing.port.layout is not None
    block = Block(crossing.name, crossing.kind, crossing.connections[0].location)
    converter = _converter(index, block, crossing.port.layout, width, maxima)
    return replace(converter, crossing=crossing.crossing)


def _converter(index: int, block: Block, layout: Layout, width: int, maxima: Limits) -> Converter:
    """A subscriber receives whole messages; a publisher sends its selection, rest defaults."""
    length_fields: tuple[str, ...] = ()
    exact = layout.fixed_size
    if block.kind is BlockKind.PUBLISHER:
        length_fields = tuple(f.path for f in layout.fields if f.selected and f.is_dynamic)
        exact = None if length_fields else default_frame_bytes(layout)
    period, deadline = _timing(block)
    return Converter(
        id=index,
        block=block.name,
        topic=block.topic or "",
        message=layout.type_name,
        layout=layout,
        bus_width=width,
        frame_bytes=exact,
        max_frame_bytes=_max_frame_bytes(block, layout, exact, maxima),
        length_fields=length_fields,
        period=period,
        deadline=deadline,
    )


def _length_known_late(field: LayoutField) -> bool:
    """Whether a sequence's byte length depends on lengths inside its elements."""
    if field.kind is not FieldKind.SEQUENCE:
        return False
    if field.element_type == "string":
        return True
    return field.element is not None and any(f.is_dynamic for f in field.element.fields)


def _scheduler(design: Design, publishers: tuple[Converter, ...]) -> Scheduler:
    """The scheduler of the publishers; the first one beyond the most it can take is refused."""
    if len(publishers) > MAX_INPUTS:
        with located(design.block(publishers[MAX_INPUTS].block).location):
            check_inputs(len(publishers), "the scheduler of the publishers")
    inputs = tuple(_scheduler_input(c, _block_of(design, c)) for c in publishers)
    return Scheduler(design.project.scheduler, inputs)


def _scheduler_input(converter: Converter, block: Block | None) -> SchedulerInput:
    exact = converter.frame_bytes is not None
    frame = converter.frame_bytes if exact else converter.max_frame_bytes
    assert frame is not None
    beats = math.ceil((CHUNK_HEADER_BYTES + frame) / (converter.bus_width // 8))
    if (
        block is not None
        and exact
        and converter.deadline is not None
        and beats > converter.deadline
    ):
        attribute = "deadline" if block.deadline is not None else "period"
        raise RfcError(
            f"{attribute} of publisher '{block.name}' ({converter.deadline} cycles) is shorter "
            f"than its transfer ({beats} beats of {converter.bus_width} bits); it can never "
            "be met",
            location=block.at(attribute),
        )
    if block is not None:  # a crossing publisher has no timing of its own
        with located(block.at("deadline" if block.deadline is not None else "period")):
            check_timing(beats, converter.deadline or beats + DEFAULT_IDLE)
    # Keyword arguments, like cocotb_sim's call of the cocotb runner in shape only.
    return SchedulerInput(
        index=converter.id,
        publisher=converter.block,
        transfer_beats=beats,
        transfer_exact=exact,
        period=converter.period,
        deadline=converter.deadline,
    )
