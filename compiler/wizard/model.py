"""The answers of a wizard session: a whole system, as plain values."""

from __future__ import annotations

from dataclasses import dataclass


# Plain records of answers: alike in shape only with other records of rfc (steps, plan).
@dataclass(frozen=True)
class ProjectAnswers:
    """The project's settings, spelled as the YAML form spells them."""

    name: str
    middleware: str
    distro: str
    fpga_part: str
    clock_mhz: float
    bus_width: int
    msg_paths: tuple[str, ...]
    scheduler: str


@dataclass(frozen=True)
class PortAnswer:
    """One accelerator port: its name and message type."""

    name: str
    message: str


@dataclass(frozen=True)
class AcceleratorAnswers:
    """An accelerator type: its kind, sources and typed ports.

    Attributes:
        skeleton: Whether to write a skeleton into `sources` (which does not exist yet).
    """

    name: str
    kind: str
    sources: str
    top: str
    reference: str
    inputs: tuple[PortAnswer, ...]
    outputs: tuple[PortAnswer, ...]
    skeleton: bool = False


@dataclass(frozen=True)
class BlockAnswers:
    """A block of the system: subscriber, accelerator instance or publisher.

    Attributes:
        name: The block name.
        kind: ``subscriber``, ``publisher`` or ``accelerator``.
        message: The message type of a subscriber or publisher.
        topic: The topic of a subscriber or publisher.
        accelerator: The accelerator type of an accelerator block.
        period: A duration (``10 ms``) or cycles, empty when none is given.
        include: The fields a subscriber passes on (dotted paths), empty for all.
    """

    name: str
    kind: str
    message: str = ""
    topic: str = ""
    accelerator: str = ""
    period: str = ""
    include: tuple[str, ...] = ()


@dataclass(frozen=True)
class ConnectionAnswer:
    """A connection between two blocks, with the ports named where a block has several."""

    source: str
    destination: str
    port: str = ""
    output: str = ""


@dataclass(frozen=True)
class SystemAnswers:
    """Everything the wizard asked: enough to write the spec."""

    project: ProjectAnswers
    accelerators: tuple[AcceleratorAnswers, ...]
    blocks: tuple[BlockAnswers, ...]
    connections: tuple[ConnectionAnswer, ...]
