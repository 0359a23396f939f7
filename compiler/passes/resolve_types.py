"""resolve-types: message types become canonical names, blocks get their typed ports.

Subscribers get one output port ``out0`` and publishers one input port ``in0`` of their
message type; an accelerator block gets the ports of its accelerator type.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.errors import RfcError, SourceLocation, did_you_mean
from rfc.ir.model import AcceleratorType, Block, BlockKind, Design, Direction, Port, Stage
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.passes.base import types_of
from rfc.spec.schema import PUBLISHER_TYPE, SUBSCRIBER_TYPE


@dataclass(frozen=True)
class ResolveTypes:
    """Resolve message and accelerator types; give every block its typed ports."""

    name: ClassVar[str] = "resolve-types"

    def apply(self, design: Design) -> Design:
        """Return the design at stage TYPED."""
        try:
            types = types_of(design.project)
        except RfcError as exc:  # the front-ends checked the distro: a user .msg is wrong
            raise relocate(exc, design.project.at("msg_paths")) from None
        accelerators = tuple(_resolve_type(types, t) for t in design.accelerators)
        by_name: dict[str, AcceleratorType] = {}
        for accelerator in accelerators:
            if accelerator.name in by_name:
                raise RfcError(
                    f"accelerator type '{accelerator.name}' is defined twice "
                    f"(first at {by_name[accelerator.name].location})",
                    location=accelerator.at("name"),
                )
            by_name[accelerator.name] = accelerator
        blocks = tuple(_resolve_block(types, block, by_name) for block in design.blocks)
        return replace(design, accelerators=accelerators, blocks=blocks, stage=Stage.TYPED)


def relocate(error: RfcError, location: SourceLocation) -> RfcError:
    """The same error, placed at a spec element (unless it already has a place)."""
    return RfcError(error.message, location=error.location or location, hint=error.hint)


def _resolve(types: MessageTypes, message: str, location: SourceLocation) -> str:
    try:
        return types.resolve(message)
    except RfcError as exc:
        raise relocate(exc, location) from None


def _resolve_port(types: MessageTypes, port: Port) -> Port:
    return replace(port, message=_resolve(types, port.message, port.at("message")))


def _resolve_type(types: MessageTypes, accelerator: AcceleratorType) -> AcceleratorType:
    return replace(
        accelerator,
        inputs=tuple(_resolve_port(types, p) for p in accelerator.inputs),
        outputs=tuple(_resolve_port(types, p) for p in accelerator.outputs),
    )


def _resolve_block(
    types: MessageTypes, block: Block, accelerators: dict[str, AcceleratorType]
) -> Block:
    if block.kind is BlockKind.ACCELERATOR:
        accelerator = accelerators.get(block.accelerator or "")
        if accelerator is None:
            known = [SUBSCRIBER_TYPE, PUBLISHER_TYPE, *accelerators]
            raise RfcError(
                f"block '{block.name}' has type '{block.accelerator}', which is neither "
                f"{SUBSCRIBER_TYPE}, {PUBLISHER_TYPE} nor an accelerator type"
                + (f" ({', '.join(accelerators)})" if accelerators else ""),
                location=block.at("type"),
                hint=did_you_mean(str(block.accelerator), known)
                or "define it under 'accelerators'",
            )
        return replace(block, ports=accelerator.ports)
    assert block.message is not None
    message = _resolve(types, block.message, block.at("message"))
    direction = Direction.OUT if block.kind is BlockKind.SUBSCRIBER else Direction.IN
    port = Port(f"{direction.value}0", direction, message, block.at("message"))
    return replace(block, message=message, ports=(port,))
