"""Accelerators that forward their input message unchanged, for any message type.

`pass_through` takes rfc's flat ports (docs/accelerators.md) for one input port ``in0`` and one
output port ``out0`` of the same type: every pin of ``out0`` is driven by the same pin of
``in0`` (fields, lengths, sub-streams), and readys flow back. It takes its ports as keywords,
so one block serves every message type; name it as a MyHDL accelerator's ``top``.
`typed_pass_through` does the same on interface objects, member by member.
"""

from __future__ import annotations

from collections.abc import Iterator

from myhdl import always_seq, block

from rfc.lib.converters.wiring import follow
from rfc.lib.interface import MessageInterface
from rfc.lib.types import Instances, Member, SignalLike


@block
def pass_through(clk: SignalLike, rst: SignalLike, **ports: SignalLike) -> Instances:
    """Forward ``in0`` to ``out0``; what only ``in0`` has is taken and dropped."""
    wires = []
    for name, target in ports.items():
        if not name.startswith("out0_"):
            continue
        partner = ports["in0_" + name.removeprefix("out0_")]
        wires.append(follow(target, partner) if name.endswith("ready") else follow(partner, target))
    unmatched = [
        signal
        for name, signal in ports.items()
        if name.startswith("in0_")
        and name.endswith("ready")
        and "out0_" + name.removeprefix("in0_") not in ports
    ]
    return wires, [take_all(clk, rst, ready) for ready in unmatched]


@block
def typed_pass_through(
    clk: SignalLike, rst: SignalLike, in0: MessageInterface, out0: MessageInterface
) -> Instances:
    """Forward interface object ``in0`` to ``out0``; readys flow back, the rest is dropped."""
    wires = [
        follow(target, source) if name == "ready" else follow(source, target)
        for name, source, target in _members(in0, out0)
    ]
    return wires, [take_all(clk, rst, ready) for ready in _unmatched_readies(in0, out0)]


@block
def take_all(clk: SignalLike, rst: SignalLike, ready: SignalLike) -> Instances:
    """Hold `ready` high after reset: whatever its stream or message brings is taken and dropped.

    A register, not a constant, so that no tool reads an initial value differently.
    """

    @always_seq(clk.posedge, reset=rst)
    def take() -> None:
        ready.next = 1

    return take


def _unmatched_readies(source: Member, target: Member) -> Iterator[SignalLike]:
    """The readies of `source`'s handshakes that `target` has no place for."""
    for name, value in vars(source).items():
        if name.startswith("_"):
            continue
        other = getattr(target, name, None)
        if other is None:
            yield from _readies(name, value)
        elif isinstance(value, MessageInterface):
            yield from _unmatched_readies(value, other)
        elif isinstance(value, list):
            for one, partner in zip(value, other, strict=True):
                if isinstance(one, MessageInterface):
                    yield from _unmatched_readies(one, partner)


def _readies(name: str, value: Member) -> Iterator[SignalLike]:
    if isinstance(value, MessageInterface):
        for inner, member in vars(value).items():
            if not inner.startswith("_"):
                yield from _readies(inner, member)
    elif isinstance(value, list):
        for member in value:
            yield from _readies(name, member)
    elif name == "ready":
        yield value


def _members(source: Member, target: Member) -> Iterator[tuple[str, SignalLike, SignalLike]]:
    """Pairs of same-placed signals of two interface objects (what only `source` has is left)."""
    for name, value in vars(target).items():
        if name.startswith("_") or not hasattr(source, name):
            continue
        yield from _pairs(name, getattr(source, name), value)


def _pairs(
    name: str, source: Member, target: Member
) -> Iterator[tuple[str, SignalLike, SignalLike]]:
    if isinstance(target, MessageInterface):
        yield from _members(source, target)
    elif isinstance(target, list):
        for one, other in zip(source, target, strict=True):
            yield from _pairs(name, one, other)
    else:
        yield name, source, target
