"""Stream helpers the image stages share: bytes out of beats, elements into beats, the header.

rfc hands an image's ``data`` to a stage as a stream of beats of the bus width, elements in
order, every beat full but the last, its length known before the first beat
(docs/accelerators.md). `byte_reader` turns it into one pixel byte per cycle; `beat_packer`
gathers the stage's output elements into beats again. A stage holds its input message until
its output message is taken, so the header it passes on reads the subscriber's registers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from myhdl import Signal, always, always_comb, always_seq, block, intbv


@dataclass(frozen=True)
class Shape:
    """What a stage's output image is, against its input's.

    Attributes:
        encoding: Its encoding (sensor_msgs/image_encodings).
        pixel_bytes: Bytes per pixel (step = pixel_bytes · width).
        halved: Whether width and height are half the input's (floor).
    """

    encoding: str
    pixel_bytes: int
    halved: bool


def beat_bytes(stream: Any) -> int:
    """Bytes per beat of a stream interface object."""
    return len(stream.data) // 8


@block
def byte_reader(clk: Any, rst: Any, stream: Any, byte: Any, valid: Any, take: Any) -> Any:
    """One byte of `stream` per cycle: `byte` is valid with `valid`, taken with `take`.

    A message's first beat is the one taken when none of its bytes are left, so the stream's
    ``length`` counts the bytes of each message without a separate start signal.
    """
    width = beat_bytes(stream)
    data, s_valid, s_ready, length = stream.data, stream.valid, stream.ready, stream.length
    beat = Signal(intbv(0)[8 * width :])
    left = Signal(intbv(0, min=0, max=width + 1))
    remaining = Signal(intbv(0)[len(length) :])
    room = Signal(bool(0))

    @always_comb
    def handshake() -> None:
        room.next = left == 0 or (left == 1 and take)
        byte.next = beat[8:0]
        valid.next = left != 0

    @always_comb
    def ready() -> None:
        s_ready.next = room

    @always_seq(clk.posedge, reset=rst)
    def load() -> None:
        if s_valid and room:
            due = intbv(0)[len(length) :]
            due[:] = length if remaining == 0 else remaining
            if due >= width:
                left.next = width
                remaining.next = due - width
            else:
                left.next = due
                remaining.next = 0
            beat.next = data
        elif take:
            beat.next = beat >> 8
            left.next = left - 1

    return handshake, ready, load


@block
def beat_packer(
    clk: Any,
    rst: Any,
    element: Any,
    valid: Any,
    accept: Any,
    flush: Any,
    stream: Any,
    empty: Any,
) -> Any:
    """Elements into beats of `stream`, low bytes first; `flush` sends a partial last beat.

    An element is taken on a cycle where `valid` and `accept` are high; `empty` says that
    nothing is held. One element per cycle goes through while the stream takes its beats.
    """
    size = len(element) // 8
    width = beat_bytes(stream)
    per_beat = width // size
    data, s_valid, s_ready = stream.data, stream.valid, stream.ready
    pack = Signal(intbv(0)[8 * width :])
    count = Signal(intbv(0, min=0, max=per_beat + 1))
    beat = Signal(intbv(0)[8 * width :])
    full = Signal(bool(0))
    free = Signal(bool(0))

    @always_comb
    def status() -> None:
        free.next = not full or s_ready
        empty.next = count == 0 and not full

    @always_comb
    def outputs() -> None:
        accept.next = free
        data.next = beat
        s_valid.next = full

    @always_seq(clk.posedge, reset=rst)
    def gather() -> None:
        if full and s_ready:
            full.next = 0
        if valid and free:
            word = intbv(0)[8 * width :]
            word[:] = pack
            for index in range(per_beat):  # bit by bit: Verilog wants constant slice bounds
                if count == index:
                    for bit in range(8 * size):
                        word[8 * size * index + bit] = element[bit]
            if count == per_beat - 1:
                beat.next = word
                full.next = 1
                pack.next = 0
                count.next = 0
            else:
                pack.next = word
                count.next = count + 1
        elif flush and count != 0 and free:
            beat.next = pack
            full.next = 1
            pack.next = 0
            count.next = 0

    return status, outputs, gather


@block
def line_memory(clk: Any, read: Any, read_at: Any, out: Any, write: Any, write_at: Any,
                value: Any, depth: int) -> Any:  # fmt: skip
    """One image row: a read registered into `out`, a write; block RAM in the build."""
    words = [Signal(intbv(0)[len(value) :]) for _ in range(depth)]

    @always(clk.posedge)
    def access() -> None:
        if write:
            words[write_at].next = value
        if read:
            out.next = words[read_at]

    return access


@block
def constant_text(clk: Any, rst: Any, text: str, stream: Any, start: Any, done: Any) -> Any:
    """Send `text` on a string stream once per message, from `start`; `done` once it is sent."""
    width = beat_bytes(stream)
    encoded = text.encode()
    beats = [encoded[i : i + width] for i in range(0, len(encoded), width)]
    rom = (*(int.from_bytes(b, "little") for b in beats), 0)
    data, s_valid, s_ready, length = stream.data, stream.valid, stream.ready, stream.length
    index = Signal(intbv(0, min=0, max=len(rom)))
    sent = Signal(bool(0))
    last = len(beats)

    @always_comb
    def outputs() -> None:
        length.next = len(encoded)
        data.next = rom[index]
        s_valid.next = start and not sent and index != last
        done.next = sent

    @always_seq(clk.posedge, reset=rst)
    def walk() -> None:
        if not start:
            index.next = 0
            sent.next = 0
        elif not sent:
            if index == last:
                sent.next = 1
            elif s_ready:
                index.next = index + 1

    return outputs, walk


@block
def pass_header(incoming: Any, outgoing: Any) -> Any:
    """The input's stamp and frame_id on the output: the subscriber's registers, streamed."""
    stamp, out_stamp = incoming.stamp, outgoing.stamp
    frame, out_frame = incoming.frame_id, outgoing.frame_id

    @always_comb
    def header() -> None:
        out_stamp.sec.next = stamp.sec
        out_stamp.nanosec.next = stamp.nanosec
        out_frame.length.next = frame.length
        out_frame.data.next = frame.data
        out_frame.valid.next = frame.valid
        frame.ready.next = out_frame.ready

    return header
