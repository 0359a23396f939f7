"""check-hardware: the rules of the logic, applied before anything is generated.

`rfc check` runs this pass, so it refuses what `rfc build` would: names that no converter or
accelerator port can have (`rfc.lib.converters.ports.check_names`), accelerators whose sources
do not have the ports of their messages (MyHDL blocks by their parameters, VHDL entities port
by port), a message with strings or sequences fanned out to several blocks, and publisher
buffers beyond the part's block RAM. The lowering calls the same functions; this pass changes
nothing in the design but its stage.
"""

from __future__ import annotations

import inspect
from collections import defaultdict
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, replace
from math import ceil
from typing import Any, ClassVar

from rfc.errors import RfcError, SourceLocation, located
from rfc.hls.ports import accelerator_core, input_holds
from rfc.ir.infrastructure import Converter
from rfc.ir.model import (
    AcceleratorKind,
    AcceleratorType,
    Block,
    BlockKind,
    Design,
    Direction,
    Stage,
)
from rfc.lib.converters.buffer_sizes import Buffer, buffers_of
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Port, PortRole, Side, accelerator_signature, ports_of
from rfc.lib.converters.prefix_plan import SLACK_BEATS, checking_plan
from rfc.lib.converters.steps import ROOT, Payload, Plan
from rfc.lib.devices import block_rams, bram36
from rfc.messages.limits import Limits
from rfc.passes.frame_size import frame_bound
from rfc.spec.python_sources import function_in
from rfc.toolchain import GhdlError, VhdlEntity, read_entities

#: Pad bytes a ROS 2 frame may carry after its message (to a multiple of 4).
CDR_PAD = 3
#: What a frame guard's buffer holds, as the report and the block-RAM check name it.
WHOLE_FRAME = "(whole frame)"
#: What a prefix guard's buffer holds: the frame up to its last sequence (named after it).
PREFIX = "(frame before '{}')"
#: Ports every accelerator has besides its message pins.
CLOCK, RESET = "clk", "rst"
_CLOCK_PORTS = (
    Port(CLOCK, 1, Direction.IN, PortRole.CLOCK),
    Port(RESET, 1, Direction.IN, PortRole.RESET),
)


@dataclass(frozen=True)
class CheckHardware:
    """Refuse, with the spec's locations, every design the logic cannot be made of."""

    name: ClassVar[str] = "check-hardware"

    def apply(self, design: Design) -> Design:
        """Return `design` at stage CHECKED, or raise the first rule it breaks."""
        infrastructure = design.infrastructure
        assert infrastructure is not None, "check-hardware runs after derive-infrastructure"
        limits, width = design.project.maxima, design.project.bus_width
        buffers: dict[str, tuple[Buffer, ...]] = {}
        for side, converters in (
            (Side.SUBSCRIBER, infrastructure.subscribers),
            (Side.PUBLISHER, infrastructure.publishers),
        ):
            for converter in converters:
                with located(converter_location(design, converter)):
                    chosen = converter_plan(converter, limits, record_first(design, converter))
                if side is Side.PUBLISHER and (held := buffers_of(chosen)):
                    buffers[converter.block] = held
                if side is Side.SUBSCRIBER and (
                    guard := subscriber_guard(converter, chosen, limits)
                ):
                    buffers[converter.block] = (guard,)
        checked: set[str] = set()
        for block in design.blocks_of(BlockKind.ACCELERATOR):
            if block.name in infrastructure.software:
                continue
            accelerator = design.accelerator(block.accelerator or "")
            with located(accelerator.location):
                signatures = accelerator_signatures(block, width, limits)
            if accelerator.name not in checked:
                checked.add(accelerator.name)
                check_sources(accelerator, signatures)
            if accelerator.kind is AcceleratorKind.HLS:
                buffers[block.name] = hls_fifos(block, width, limits)
        check_fan_out(design)
        check_buffer_memory(design, buffers)
        return replace(design, stage=Stage.CHECKED)


def converter_location(design: Design, converter: Converter) -> SourceLocation:
    """Where a converter's block was written (a crossing's: the project, which implies it)."""
    blocks = (b.location for b in design.blocks if b.name == converter.block)
    return next(blocks, design.project.location)


def converter_plan(converter: Converter, limits: Limits, record_first: bool = False) -> Plan:
    """The plan of a converter of the model (its names checked).

    `record_first`: a publisher's producer gives the record by its last stream's first beat.
    """
    return replace(plan(converter.layout, converter.bus_width, limits), record_first=record_first)


def record_first(design: Design, converter: Converter) -> bool:
    """Whether a publisher's producer is record-first: a MyHDL accelerator (its contract).

    A MyHDL block sets every field and length of an output message by the first beat of the
    message's last stream (docs/accelerators.md); HLS cores may set a length after writing
    the stream, and VHDL entities promise nothing, so their publishers buffer every stream.
    """
    infrastructure = design.infrastructure
    assert infrastructure is not None
    producer: str | None
    if converter.crossing is not None:
        producer = converter.crossing.hardware.split(".")[0]
    else:
        producer = next(
            (
                c.source.block
                for c in infrastructure.hardware_connections
                if c.destination.block == converter.block
            ),
            None,
        )
    if producer is None or producer not in {b.name for b in design.blocks}:
        return False
    block = design.block(producer)
    if block.kind is not BlockKind.ACCELERATOR or block.name in infrastructure.software:
        return False
    return design.accelerator(block.accelerator or "").kind is AcceleratorKind.MYHDL


def accelerator_signatures(block: Block, width: int, limits: Limits) -> dict[str, tuple[Port, ...]]:
    """Each message port's signature on an accelerator block, by port name."""
    signatures = {}
    for port in block.ports:
        assert port.layout is not None
        side = Side.SUBSCRIBER if port.direction is Direction.IN else Side.PUBLISHER
        signatures[port.name] = accelerator_signature(
            plan(port.layout, width, limits), side, port.name
        )
    return signatures


def flat_ports(signatures: Mapping[str, Sequence[Port]]) -> tuple[Port, ...]:
    """Clock, reset and every message pin: the flat ports of an accelerator's entity."""
    return (*_CLOCK_PORTS, *(p for ports in signatures.values() for p in ports))


def check_sources(accelerator: AcceleratorType, signatures: Mapping[str, Sequence[Port]]) -> None:
    """Check that an accelerator's source has the ports of its messages.

    Raises:
        RfcError: The MyHDL block or VHDL entity has other ports.
    """
    if not all(path.exists() for path in accelerator.sources):
        return  # `rfc stub` reads a spec whose source is still to be written
    check = _SOURCE_CHECKS.get(accelerator.kind)
    if check is not None:
        check(accelerator, signatures)


def block_function(accelerator: AcceleratorType) -> Any:
    """The MyHDL block function of a MyHDL accelerator (imported from its source)."""
    if accelerator.block_function is not None:
        return accelerator.block_function
    python = next(p for p in accelerator.sources if p.suffix == ".py")
    function = function_in(python, accelerator.top or accelerator.name, accelerator, "MyHDL block")
    definition = getattr(function, "definition", None)  # an @rfc.accelerator in a YAML project
    return getattr(definition, "block_function", None) or function


def takes_interfaces(
    accelerator: AcceleratorType, function: Any, signatures: Mapping[str, Sequence[Port]]
) -> bool:
    """Whether the block takes interface objects (one argument per port) or flat ports.

    Raises:
        RfcError: It has the arguments of neither form.
    """
    plain = getattr(function, "func", function)  # MyHDL's @block keeps the function in .func
    try:
        parameters = inspect.signature(plain).parameters
    except (TypeError, ValueError):
        return False
    typed = [CLOCK, RESET, *signatures]
    flat = [p.name for p in flat_ports(signatures)]
    keywords = any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values())
    required = [
        n
        for n, p in parameters.items()
        if p.default is inspect.Parameter.empty and p.kind is not inspect.Parameter.VAR_KEYWORD
    ]
    if all(n in parameters for n in typed) and all(n in typed for n in required):
        return True
    missing = [] if keywords else [n for n in flat if n not in parameters]
    extra = [n for n in required if n not in flat]
    if not missing and not extra:
        return False
    if any(n in parameters for n in signatures):  # meant as interface objects
        missing = [n for n in typed if n not in parameters]
        extra = [n for n in required if n not in typed]
    problems = []
    if missing:
        problems.append(f"it lacks {_some(missing)}")
    if extra:
        problems.append(f"it also needs {_some(extra)}, which rfc does not provide")
    raise RfcError(
        f"MyHDL block '{plain.__name__}' of accelerator '{accelerator.name}' does not have "
        f"the ports of its messages: {'; '.join(problems)}",
        location=accelerator.location,
        hint=f"declare it as {plain.__name__}({', '.join(typed)}) taking one interface object "
        f"per message port (`rfc stub SPEC {accelerator.name} --lang myhdl` prints a skeleton), "
        f"or with flat ports as {plain.__name__}({_some(flat, 12)}) (docs/accelerators.md)",
    )


def _some(names: Sequence[str], shown: int = 8) -> str:
    """The first names, and how many more: a block's ports can number in the hundreds."""
    more = len(names) - shown
    return ", ".join(names[:shown]) + (f", … ({more} more)" if more > 0 else "")


def vhdl_entity(accelerator: AcceleratorType, expected: Sequence[Port]) -> VhdlEntity:
    """The entity of a VHDL accelerator, checked port by port against `expected`.

    Raises:
        RfcError: A source does not analyse, the entity is missing, or its ports differ.
    """
    top = (accelerator.top or accelerator.name).lower()
    found = None
    for source in accelerator.sources:
        try:
            entities = read_entities(source)
        except GhdlError as exc:
            raise RfcError(
                f"VHDL source '{source.name}' of accelerator '{accelerator.name}' does not "
                f"analyse:\n{exc}",
                location=accelerator.location,
            ) from None
        found = found or next((e for e in entities if e.name.lower() == top), None)
    if found is None:
        raise RfcError(
            f"no entity '{top}' in the VHDL sources of accelerator '{accelerator.name}'",
            location=accelerator.location,
            hint="name the entity with 'top:' or name it like the accelerator; "
            f"`rfc stub SPEC {accelerator.name} --lang vhdl` prints one",
        )
    actual = {p.name: p for p in found.ports}
    problems = []
    for want in expected:
        have = actual.get(want.name.lower())
        if have is None:
            problems.append(f"no port {want.name} ({_describe(want)})")
        elif (
            have.mode != want.direction.value or have.wire != want.is_wire or have.bits != want.bits
        ):
            kind = "std_logic" if have.wire else f"{have.bits}-bit vector"
            problems.append(f"{have.name} is {have.mode} {kind}, expected {_describe(want)}")
    names = {p.name.lower() for p in expected}
    problems += [
        f"port {p.name} is not part of the convention" for p in found.ports if p.name not in names
    ]
    if problems:
        raise RfcError(
            f"entity {found.name} ({found.file.name}:{found.line}) of accelerator "
            f"'{accelerator.name}' does not have the ports of its messages: " + "; ".join(problems),
            location=accelerator.location,
            hint=f"`rfc stub SPEC {accelerator.name} --lang vhdl` prints the entity to write "
            "(docs/accelerators.md)",
        )
    return found


def _describe(port: Port) -> str:
    kind = "std_logic" if port.is_wire else f"std_logic_vector({port.bits - 1} downto 0)"
    return f"{port.direction.value} {kind}"


def check_fan_out(design: Design) -> None:
    """Refuse a message with strings or sequences that feeds several blocks in the logic."""
    infrastructure = design.infrastructure
    assert infrastructure is not None
    by_source = defaultdict(list)
    for connection in infrastructure.hardware_connections:
        by_source[(connection.source.block, connection.source.port)].append(connection)
    for connections in by_source.values():
        if len(connections) < 2:
            continue
        for connection in connections:
            streamed = next(_streamed(design, connection.destination.block), None)
            if streamed is not None:
                raise RfcError(
                    f"connection {connection.source} → {connection.destination}: a message "
                    f"with strings or sequences ('{streamed}') cannot feed several blocks in "
                    "the logic",
                    location=connection.location,
                    hint="exclude the string or sequence fields, or subscribe once per block",
                )


def _streamed(design: Design, block_name: str) -> Iterator[str]:
    """The selected strings and sequences a block's inputs take."""
    for port in design.block(block_name).inputs:
        assert port.layout is not None
        for leaf in port.layout.fields:
            if leaf.selected and leaf.kind.value != "primitive":
                yield leaf.path


def subscriber_guard(converter: Converter, chosen: Plan, limits: Limits) -> Buffer | None:
    """The frame guard's buffer in front of a subscriber that streams, else None.

    A subscriber hands strings and sequences on while it parses; a guard holds the frame until
    it is known well-formed, so no part of a malformed frame reaches a consumer
    (docs/converters.md): the whole frame, or only the bytes before the message's last field
    when that is a primitive sequence after every other length (`rfc.lib.converters.
    prefix_guard`).
    """
    streamed = any(
        p.role is PortRole.TDATA or (p.role is PortRole.VALID and p.group != ROOT)
        for p in ports_of(chosen, Side.SUBSCRIBER)
    )
    if not streamed:
        return None
    lanes = converter.bus_width // 8
    checking = checking_plan(chosen)
    if checking is not None:
        last = checking.steps[-2]
        assert isinstance(last, Payload)
        empty = replace(limits, fields={**limits.fields, last.path: 0})
        prefix = frame_bound(converter.layout, empty)
        assert prefix is not None, "maxima bound every frame"
        depth = ceil(prefix / lanes) + SLACK_BEATS
        return Buffer("frame", PREFIX.format(last.path), depth, converter.bus_width)
    bound = frame_bound(converter.layout, limits)
    assert bound is not None, "maxima bound every frame"
    depth = ceil((bound + (CDR_PAD if chosen.is_cdr else 0)) / lanes)
    return Buffer("frame", WHOLE_FRAME, depth, converter.bus_width)


def check_buffer_memory(design: Design, buffers: Mapping[str, tuple[Buffer, ...]]) -> None:
    """Refuse buffers that need more block RAM than the part has, naming the largest one."""
    if not buffers:
        return
    need = {
        (block, b.path): bram36(b.bits, b.words) for block, held in buffers.items() for b in held
    }
    have, known = block_rams(design.project.fpga_part)
    if sum(need.values()) <= have:
        return
    block, path = max(need, key=lambda key: need[key])
    device = f"the {design.project.fpga_part}'s" if known else "any supported device's"
    # a crossing publisher is no block of the spec: the project stands for it
    location = next((b.location for b in design.blocks if b.name == block), design.project.location)
    largest = f"holds '{path}' of '{block}'"
    example = f"{{string: 64, fields: {{{path}: N}}}}"
    if path == WHOLE_FRAME:
        largest = f"is the frame guard of '{block}', which holds its largest frame"
        example = "{string: 64, sequence: 4096}"
    elif path.startswith(PREFIX.format("")[:-2]):
        largest = f"is the frame guard of '{block}', which holds its frames {path[7:-1]}"
        example = "{string: 64, sequence: 4096}"
    raise RfcError(
        f"the logic's buffers need {sum(need.values()):,} block RAMs of 36 Kb at the "
        f"project's maxima, more than {device} {have:,}; the largest {largest} "
        f"({need[(block, path)]:,})",
        location=location,
        hint=f"give the project smaller maxima, e.g. maxima: {example} (docs/spec.md)",
    )


def hls_fifos(block: Block, width: int, limits: Limits) -> tuple[Buffer, ...]:
    """The FIFOs an HLS block's wrapper holds its input ports' earlier streams in."""
    return tuple(buffer for _, buffer in input_holds(block, width, limits))


#: Per accelerator kind, how its source is checked against its message signatures (ROS-SW
#: functions run on messages, not ports).
_SOURCE_CHECKS: dict[
    AcceleratorKind, Callable[[AcceleratorType, Mapping[str, Sequence[Port]]], object]
] = {
    AcceleratorKind.MYHDL: lambda a, signatures: takes_interfaces(a, block_function(a), signatures),
    AcceleratorKind.VHDL: lambda a, signatures: vhdl_entity(a, flat_ports(signatures)),
    AcceleratorKind.HLS: accelerator_core,
}
