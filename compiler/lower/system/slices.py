"""Registered boundaries: a register slice on each handshake handed from one block to another.

Between a converter and an accelerator the top level puts `rfc.lib.slice` on the message's
fields and valid/ready, so that everything one block hands the next comes from a flip-flop and
no combinational path crosses from one block into another. A message with strings or
primitive sequences gets a slice on each sub-stream instead (its beats, ``tvalid`` and
``tready``, a beat every cycle); its record (the fields, the lengths the consumer reads while
the bytes stream, and ``msg_valid``/``msg_ready``) is wired directly, as are messages with
sequences of messages (element channels).
"""

from __future__ import annotations

from pathlib import Path

from rfc.lib.converters.ports import Direction
from rfc.lower.system.components import Component, slice_component
from rfc.lower.system.interfaces import MESSAGE
from rfc.lower.system.top import Interface, Terminal, TopBuilder

_VALID, _READY = f"{MESSAGE}_valid", f"{MESSAGE}_ready"
#: Names that belong to a handshake of their own (a sub-stream's), not to the message's fields.
_HANDSHAKE_ENDINGS = ("_valid", "_ready", "_last")
#: A sub-stream's beat and its handshake, as suffixes of its pins' names.
_BEAT, _TVALID, _TREADY = ("_tdata", "_tkeep", "_tlast"), "_tvalid", "_tready"

Fields = tuple[tuple[str, int, bool], ...]


class RegisterSlices:
    """The slices of a system and the components (one per message shape) they need.

    Args:
        prefix: The project's identifier, which the slice entities' names start with.
        directory: Where the VHDL goes.
    """

    def __init__(self, prefix: str, directory: Path) -> None:
        self.prefix, self.directory = prefix, directory
        self.components: list[Component] = []
        self._by_shape: dict[Fields, Component] = {}

    def insert(
        self, builder: TopBuilder, target: Interface, label: str, streams: bool = True
    ) -> Interface:
        """Put the slices labelled from `label` in front of `target`, wired to it.

        `streams` false leaves a streamed message's sub-streams direct: a publisher that streams
        its last stream through takes the producer's `msg_valid` as the end of its beats, which
        a slice holding the last beats would contradict.

        Returns:
            The interface to wire the producer to: the slices' input sides where there are
            slices, `target`'s own pins elsewhere.
        """
        if _sliceable(builder, target):
            names = [n for n in target if n not in (_VALID, _READY)]
            return self._slice(builder, target, label, names, _VALID, _READY)
        interface = dict(target)
        for stream in _streams(builder, target) if streams else []:
            beat = [f"{stream}{suffix}" for suffix in _BEAT if f"{stream}{suffix}" in target]
            valid, ready = f"{stream}{_TVALID}", f"{stream}{_TREADY}"
            interface |= self._slice(builder, target, f"{label}_{stream}", beat, valid, ready)
        return interface

    def _slice(
        self, builder: TopBuilder, target: Interface, label: str, names: list[str], valid: str,
        ready: str,
    ) -> dict[str, Terminal]:  # fmt: skip
        """One slice over the pins `names` of `target` and its handshake `valid`/`ready`."""
        fields = tuple(
            (name, builder.port(target[name]).bits, builder.port(target[name]).wire)
            for name in names
        )
        component = self._by_shape.get(fields)
        if component is None:
            name = f"{self.prefix}_slice{len(self._by_shape)}"
            component = slice_component(fields, self.directory, name)
            self._by_shape[fields] = component
            self.components.append(component)
        builder.cell(label, component.entity)
        for name, _, _ in fields:
            builder.wire(Terminal(label, f"m_{name}"), target[name])
        builder.wire(Terminal(label, "m_valid"), target[valid])
        builder.wire(target[ready], Terminal(label, "m_ready"))
        inputs = {name: Terminal(label, f"s_{name}") for name, _, _ in fields}
        return {**inputs, valid: Terminal(label, "s_valid"), ready: Terminal(label, "s_ready")}


def _sliceable(builder: TopBuilder, target: Interface) -> bool:
    """A message of fields and one handshake, every field an input of the consumer."""
    if _VALID not in target or _READY not in target:
        return False
    others = [n for n in target if n not in (_VALID, _READY)]
    if any(n.endswith(_HANDSHAKE_ENDINGS) for n in others):
        return False
    return all(builder.port(target[n]).mode is Direction.IN for n in others)


def _streams(builder: TopBuilder, target: Interface) -> list[str]:
    """The sub-streams of a message without element channels, by name; none otherwise."""
    channels = [n for n in target if n.endswith(("_valid", "_ready")) and n not in (_VALID, _READY)]
    if channels:
        return []
    streams = [n.removesuffix(_TVALID) for n in target if n.endswith(_TVALID)]
    return [
        stream
        for stream in streams
        if f"{stream}_tdata" in target
        and f"{stream}{_TREADY}" in target
        and builder.port(target[f"{stream}{_TREADY}"]).mode is Direction.OUT
        and all(
            builder.port(target[f"{stream}{suffix}"]).mode is Direction.IN
            for suffix in (*_BEAT, _TVALID)
            if f"{stream}{suffix}" in target
        )
    ]
