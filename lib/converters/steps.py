"""The steps a converter walks through, and the plan that holds them (built by `plan`).

Subscriber and publisher execute the same plan, one reading and one writing the frame:

* a `Record` is a run of fixed-size items — primitives, the uint32 length prefix that ends it,
  the CDR encapsulation header — whose offsets are static relative to the record's start. The
  first record starts at the frame's first byte, so its offsets are the layout's static offsets.
  Later records start wherever the preceding strings and sequences ended: CDR aligns each
  record's start at run time (`Record.align`); inside a record no item is more aligned than its
  first, so every offset stays static. This is the paper's Algorithm 1 folded at compile time.
* a `Payload` is the characters of a string or the elements of a primitive sequence, streamed.
* a `Loop` ... `Next` pair repeats the element steps of a sequence of messages or of strings;
  each element's fields form one record on an element channel.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from rfc.messages.layout import Layout, LayoutField
from rfc.messages.limits import Limits

#: Name of the root channel: the handshake of a whole message is ``msg_valid`` / ``msg_ready``.
ROOT = "msg"


class SlotRole(StrEnum):
    """What the bytes of a record slot hold."""

    FIELD = "field"
    """A primitive leaf of the message."""
    LENGTH = "length"
    """The uint32 prefix of the string or sequence that follows the record."""
    ENCAPSULATION = "encapsulation"
    """ROS 2's 4-byte CDR header: 00 01 (little-endian CDR) and two option bytes."""


@dataclass(frozen=True)
class Slot:
    """A fixed-size item inside a record.

    Attributes:
        offset: Bytes from the record's first byte.
        size: Bytes on the wire.
        role: What the bytes hold.
        field: The leaf (FIELD) or the string/sequence the prefix belongs to (LENGTH).
        port: Accelerator-side port of a selected FIELD, else None.
    """

    offset: int
    size: int
    role: SlotRole
    field: LayoutField | None = None
    port: str | None = None


@dataclass(frozen=True)
class Record:
    """A run of slots with static offsets relative to its start.

    Attributes:
        align: Alignment of the record's start (relative to the CDR payload) that the converter
            establishes at run time by skipping or inserting padding; 1 when none is needed.
        size: Bytes from the first byte of the first slot to the last byte of the last slot.
        slots: The slots in order.
        channel: Index of the channel whose element the record belongs to (0: the message).
    """

    align: int
    size: int
    slots: tuple[Slot, ...]
    channel: int


@dataclass(frozen=True)
class Payload:
    """The characters of a string or the elements of a primitive sequence.

    Attributes:
        field: The leaf.
        path: Its full path, through enclosing sequences.
        channel: Channel whose record holds the length port.
        element_size: Bytes per element (1 for strings).
        element_align: CDR alignment of the first element when there is one (1: none).
        terminator: Whether a NUL byte follows the characters (CDR strings); the length prefix
            counts it, the sub-stream and the length port do not.
        maximum: Most characters or elements accepted.
        stream: Prefix of the accelerator-side sub-stream ports, None when not selected.
        length_port: Port holding the character or element count, None when not selected.
    """

    field: LayoutField
    path: str
    channel: int
    element_size: int
    element_align: int
    terminator: bool
    maximum: int
    stream: str | None
    length_port: str | None

    @property
    def is_bool(self) -> bool:
        """Whether elements are bools, which the converters normalize to 0 or 1."""
        return self.field.element_type == "bool"


@dataclass(frozen=True)
class Loop:
    """The start of a sequence of messages or of strings: its count, then its elements.

    Attributes:
        field: The sequence leaf.
        path: Its full path.
        channel: Channel whose record holds the count port.
        element_channel: Channel of the elements.
        maximum: Most elements accepted.
        count_port: Port holding the element count, None when not selected.
        next: Index of the matching `Next` step.
    """

    field: LayoutField
    path: str
    channel: int
    element_channel: int
    maximum: int
    count_port: str | None
    next: int


@dataclass(frozen=True)
class Next:
    """The end of one element: hand its record over, then repeat or leave the loop.

    Attributes:
        loop: Index of the matching `Loop` step.
        channel: The element channel.
    """

    loop: int
    channel: int


@dataclass(frozen=True)
class End:
    """The end of the message: check what follows, then hand the message's record over."""


Step = Record | Payload | Loop | Next | End


@dataclass(frozen=True)
class Channel:
    """A record handed over with a valid/ready handshake: the message, or one element.

    Attributes:
        index: Position in `Plan.channels`; 0 is the message itself.
        name: Prefix of the handshake ports: ``msg`` for the message, else the sequence's port.
        path: Path of the sequence whose elements it carries ("" for the message).
        parent: Index of the enclosing channel, None for the message.
        selected: Whether the accelerator sees it (the message always; an element channel when
            any of its element's leaves is selected).
    """

    index: int
    name: str
    path: str
    parent: int | None
    selected: bool


@dataclass(frozen=True)
class Plan:
    """Everything a converter generator needs to know about one message at one bus width.

    Attributes:
        layout: The flattened, selected layout.
        width: Bus width in bytes.
        limits: Configured maxima.
        steps: What the converter does, in order; the last step is `End`.
        channels: The message channel, then one per sequence of messages or strings.
        record_first: Publishers: the producer gives every field and length by the first beat
            of the message's last stream (docs/accelerators.md), so that stream may go straight
            through (`streamed_last`).
    """

    layout: Layout
    width: int
    limits: Limits
    steps: tuple[Step, ...]
    channels: tuple[Channel, ...]
    record_first: bool = False

    @property
    def is_cdr(self) -> bool:
        """Whether the frame is ROS 2 CDR (aligned primitives, NUL-terminated strings)."""
        return self.layout.is_cdr

    @property
    def store_and_forward(self) -> bool:
        """Whether a publisher must buffer a whole frame to learn its length.

        The frame length is known before the first byte only when it follows from the lengths
        of top-level strings and sequences: every element of every sequence of messages must
        be one record of static size (so all elements have the same stride). Sequences of
        strings, and elements holding strings or sequences, need the buffer.
        """
        return any(
            not (isinstance(self.steps[i + 1], Record) and self.steps[i + 2] is self.steps[s.next])
            for i, s in enumerate(self.steps)
            if isinstance(s, Loop)
        )

    @property
    def streamed_last(self) -> int | None:
        """The step of the stream a publisher passes straight through, None when it buffers all.

        A record-first producer's last stream needs no buffer when it is the message's last
        field, at the top level, selected, in a frame whose length follows from top-level
        lengths: the publisher starts the frame at that stream's first beat.
        """
        at = len(self.steps) - 2
        last = self.steps[at] if at >= 0 else None
        if (
            not self.record_first
            or self.store_and_forward
            or not isinstance(last, Payload)
            or last.channel != 0
            or not (last.stream and last.length_port)
        ):
            return None
        return at

    def payload(self, at: int) -> Payload:
        """The step at `at`, which the caller knows is a `Payload` (a sub-stream's step)."""
        step = self.steps[at]
        assert isinstance(step, Payload), f"step {at} is a {type(step).__name__}, not a Payload"
        return step

    def loop(self, at: int) -> Loop:
        """The step at `at`, which the caller knows is a `Loop`."""
        step = self.steps[at]
        assert isinstance(step, Loop), f"step {at} is a {type(step).__name__}, not a Loop"
        return step

    def length_ports(self) -> list[tuple[int, str]]:
        """The steps whose count has a port (selected strings, sequences, loops), with it."""
        found = []
        for at, step in enumerate(self.steps):
            port = None
            if isinstance(step, Payload):
                port = step.length_port
            elif isinstance(step, Loop):
                port = step.count_port
            if port:
                found.append((at, port))
        return found

    def records(self) -> list[tuple[int, Record]]:
        """Return the record steps with their step indices."""
        return [(i, s) for i, s in enumerate(self.steps) if isinstance(s, Record)]
