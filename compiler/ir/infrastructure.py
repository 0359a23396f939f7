"""What derive-infrastructure makes explicit: the parts of the system the spec leaves implicit.

This is the contract later generators build on. Converters get their selected `Layout` and the
bus width; the manager gets the ids of the wire protocol (docs/protocol.md); the publisher side gets
the frame-length circuits and buffers (paper §4.2); the scheduler gets one input per publisher
with its timing (paper §6).

Placement: ROS-SW accelerators run on the processor, every other block in the logic. A
subscriber is in the logic when it feeds a hardware block, a publisher when a hardware block
feeds it. Where a connection crosses between a hardware and a ROS-SW accelerator, the logic
needs a converter the spec does not declare: a *crossing* publisher (hardware → software) or
subscriber (software → hardware), named after the hardware port it serves.

Numbering: subscribers and publishers in the logic are numbered separately, each from 0: the
declared ones in the order the spec declares them, then the crossing ones in connection order.
A subscriber's id is the ``id`` of the PS→PL chunks it receives, a publisher's id the ``id`` of
the PL→PS chunks it sends, and also its scheduler input index — so for the fixed-priority
schedulers the publisher declared first has the highest priority.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from rfc.ir.model import Connection
from rfc.messages.layout import Layout

#: Bytes of the chunk header (u16 id, u16 flags, u32 length) in front of every DMA transfer.
CHUNK_HEADER_BYTES = 8


# An enum then a record, like rfc.runtime.core's QueuePolicy in shape only: DMA streams.
class DmaDirection(StrEnum):
    """The two AXI-Stream channels between the processor (PS) and the logic (PL)."""

    PS_TO_PL = "ps_to_pl"
    PL_TO_PS = "pl_to_ps"


@dataclass(frozen=True)
class Crossing:
    """Where a converter the spec does not declare joins the logic to the processor.

    Attributes:
        hardware: ``Block.port`` of the hardware accelerator port the converter serves (an
            output for a crossing publisher, an input for a crossing subscriber).
        software: ``Block.port`` of the ROS-SW ports on the processor side: the inputs a
            crossing publisher's messages go to, or the one output feeding a crossing
            subscriber.
    """

    hardware: str
    software: tuple[str, ...]


@dataclass(frozen=True)
class Converter:
    """A subscriber or publisher converter, with everything its generator needs.

    Attributes:
        id: The chunk id of the wire protocol (subscribers and publishers counted apart).
        block: The block it implements.
        topic: The ROS topic.
        message: Canonical message type.
        layout: The message layout; ``selected`` marks the fields the accelerators use
            (subscriber: presents them; publisher: receives them, others get defaults).
        bus_width: Bits per beat of its AXI-Stream side.
        frame_bytes: Exact bytes of every frame when known at compile time, else None.
        max_frame_bytes: The largest frame accepted or produced (exact when static).
        length_fields: Publishers: the selected variable-length fields whose run-time lengths
            feed the frame-length circuit (paper Algorithm 1); empty when none is needed.
        period: Clock cycles between messages, when the spec gives it.
        deadline: Relative deadline in clock cycles (the period when only that is given).
        crossing: For a converter derived at a hardware/software crossing: where it sits
            (its `block` is then a derived name, not a block of the design; `topic` is empty).
    """

    id: int
    block: str
    topic: str
    message: str
    layout: Layout
    bus_width: int
    frame_bytes: int | None
    max_frame_bytes: int
    length_fields: tuple[str, ...] = ()
    period: int | None = None
    deadline: int | None = None
    crossing: Crossing | None = None

    @property
    def needs_frame_length(self) -> bool:
        """Whether a frame-length circuit must compute the frame's length at run time."""
        return bool(self.length_fields)


@dataclass(frozen=True)
class DmaChannel:
    """One DMA channel and the converters on its end, indexed by chunk id."""

    direction: DmaDirection
    width: int
    converters: tuple[str, ...]

    @property
    def name(self) -> str:
        """The AXI DMA's name of the channel: mm2s feeds the logic, s2mm drains it."""
        return "mm2s" if self.direction is DmaDirection.PS_TO_PL else "s2mm"


@dataclass(frozen=True)
class SchedulerInput:
    """One requester of the PL→PS scheduler: a publisher and its timing.

    Attributes:
        index: Scheduler input (= publisher id); lower wins under fixed priorities.
        publisher: The publisher block.
        transfer_beats: Beats of one transfer, chunk header included: exact, or the bound.
        transfer_exact: Whether `transfer_beats` is exact rather than a bound.
        period: Clock cycles between messages, when given.
        deadline: Relative deadline in clock cycles, when given (implicit: the period).
    """

    index: int
    publisher: str
    transfer_beats: int
    transfer_exact: bool
    period: int | None
    deadline: int | None


@dataclass(frozen=True)
class Scheduler:
    """The PL→PS scheduler: its algorithm (``auto`` until the DSE picks) and its inputs.

    Attributes:
        algorithm: LRU, NPFP, PFP, ROEDF, LOEDF, LST, ``auto``, or (once resolve-scheduler
            has chosen) a composition in `rfc.lib.schedulers.spec.parse_scheduler`'s syntax,
            such as ``LRU(LOEDF,LST)``.
        inputs: One per publisher, by id.
        reason: Why resolve-scheduler chose the algorithm (empty when the spec named it).
    """

    algorithm: str
    inputs: tuple[SchedulerInput, ...]
    reason: str = ""


@dataclass(frozen=True)
class Buffer:
    """A field a publisher must hold until the lengths it waits for are known.

    The chunk header carries the whole frame length, so a publisher cannot send its first byte
    before every length is known. Lengths inside the elements of a sequence (strings, nested
    sequences) arrive one element at a time, so that sequence's bytes are buffered
    (paper §4.2).
    """

    publisher: str
    field: str
    max_bytes: int


@dataclass(frozen=True)
class Infrastructure:
    """Everything derived from the spec: converters, DMA, scheduler and buffers.

    Attributes:
        subscribers: The subscriber converters in the logic, by id.
        publishers: The publisher converters in the logic, by id.
        dma: The two DMA channels.
        scheduler: The PL→PS scheduler.
        buffers: Publisher fields held until their lengths are known.
        hardware_connections: Every connection inside the logic: the design's connections
            between hardware blocks, plus, at each crossing, the connection from the hardware
            output to its crossing publisher (port ``in0``) or from a crossing subscriber (port
            ``out0``) to the hardware input. Equal to the design's connections when no
            accelerator runs in software.
        software: Names of the blocks that run on the processor (ROS-SW accelerators).
    """

    subscribers: tuple[Converter, ...]
    publishers: tuple[Converter, ...]
    dma: tuple[DmaChannel, ...]
    scheduler: Scheduler
    buffers: tuple[Buffer, ...]
    hardware_connections: tuple[Connection, ...] = ()
    software: tuple[str, ...] = ()
