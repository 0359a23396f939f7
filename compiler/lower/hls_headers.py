"""``hls/<accelerator>_messages.h``: the header each struct-taking HLS accelerator includes.

Written by ``rfc build`` (with or without the logic) for every HLS accelerator whose top
function takes message structs or streams (`rfc.hls.c_types`), so that it can be developed
and run in Vitis HLS; `rfc sim` compiles its C simulation against the same text.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from rfc.errors import RfcError
from rfc.hls.c_types import hls_header, message_structs
from rfc.hls.signature import ArgumentKind, read_top_function
from rfc.ir.model import AcceleratorKind, AcceleratorType, Block, BlockKind, Design, Direction
from rfc.lib.converters.ports import Port
from rfc.lower.artifacts import Artifact, BuildOptions
from rfc.lower.system.interfaces import accelerator_pins

#: Bus width the signatures are read at: a struct does not depend on it.
SIGNATURE_WIDTH = 64


def hls_headers(design: Design, options: BuildOptions) -> Iterable[Artifact]:
    """The header of every HLS accelerator whose top function takes structs or streams."""
    del options  # the same with or without the logic
    for accelerator in design.accelerators:
        if accelerator.kind is not AcceleratorKind.HLS or not _takes_structs(accelerator):
            continue
        block = first_block(design, accelerator)
        if block is None:
            continue
        signatures, directions = port_signatures(design, block)
        structs = message_structs(signatures, directions)
        text = hls_header(accelerator.name, structs, accelerator.top)
        yield Artifact(f"hls/{accelerator.name}_messages.h", "HLS message header", text)


def _takes_structs(accelerator: AcceleratorType) -> bool:
    sources = [p for p in accelerator.sources if p.suffix != ".h"]
    try:
        arguments = read_top_function(sources, accelerator.top or accelerator.name)
    except RfcError:  # reported where the function is needed: the logic and `rfc sim`
        return False
    return any(a.kind is not ArgumentKind.SCALAR for a in arguments)


def first_block(design: Design, accelerator: AcceleratorType) -> Block | None:
    """A block of the accelerator type (they share its ports' layouts), if any."""
    return next(
        (b for b in design.blocks_of(BlockKind.ACCELERATOR) if b.accelerator == accelerator.name),
        None,
    )


def port_signatures(
    design: Design, block: Block
) -> tuple[Mapping[str, tuple[Port, ...]], Mapping[str, Direction]]:
    """The message signature and direction of every port of an accelerator block."""
    maxima = design.project.maxima
    signatures = {
        port.name: tuple(pin.signal for pin in accelerator_pins(port, SIGNATURE_WIDTH, maxima))
        for port in block.ports
    }
    return signatures, {port.name: port.direction for port in block.ports}
