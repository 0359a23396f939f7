"""The image pipeline's three stages as MyHDL accelerators on typed streams, a pixel per cycle.

Each stage takes a sensor_msgs/Image interface object (``header``, ``height``, ``width`` and
the ``data`` stream) and gives one, keeping the input's stamp and frame_id:

- `rgb_to_gray`: rgb8 in, mono8 out, gray = (4899 R + 9617 G + 1868 B + 8192) >> 14;
- `downscale`: mono8 in, half width and height (floor) out, each pixel the rounded mean
  (a + b + c + d + 2) >> 2 of its 2x2 block, an odd last row or column dropped;
- `integral_image`: mono8 in, 32SC1 out (little-endian uint32, step 4·width), each pixel the
  sum of the input over the rows and columns up to it.

The data streams like the subscriber's: each stage sets its output's fields and lengths before
its first output beat and raises the output message's ``valid`` once every beat is taken and
its input message is valid; it takes the input message (``ready``) with the output. An output
that has ``encoding``, ``step`` or ``is_bigendian`` (the connection selects them) gets them.
Downscale and IntegralImage keep one image row in block RAM: images at most `MAX_WIDTH` pixels
wide (wider ones alias rows and give wrong pixels).
"""

from __future__ import annotations

from typing import Any

from myhdl import Signal, always_comb, always_seq, block, intbv
from pixel_streams import (
    Shape,
    beat_bytes,
    beat_packer,
    byte_reader,
    constant_text,
    line_memory,
    pass_header,
)

from rfc.lib.arith.dot import dot_latency
from rfc.lib.arith.dot_hdl import constant_dot
from rfc.lib.fixed import FixedFormat

#: The widest image Downscale and IntegralImage keep a row of (full HD fits).
MAX_WIDTH = 2048


GRAY, HALF_GRAY, INTEGRAL = (
    Shape("mono8", 1, False),
    Shape("mono8", 1, True),
    Shape("32SC1", 4, False),
)
#: OpenCV's integer BT.601 luma weights for R, G and B, scaled by 2**14.
GRAY_WEIGHTS = (4899, 9617, 1868)
#: The luma's fixed-point format: the weights are 0.299, 0.587 and 0.114 in it, the bytes raw
#: integers of it, and a pixel's luma (at most 255 raw) fits without saturating.
LUMA = FixedFormat(15, 14)


@block
def rgb_to_gray(clk: Any, rst: Any, rgb: Any, gray: Any) -> Any:
    """sensor_msgs/Image rgb (rgb8) in, gray (mono8) out: one pixel per cycle.

    The luma is `rfc.lib.arith`'s dot product with constant coefficients: the bytes as raw
    integers of Q1.14 times `GRAY_WEIGHTS` (0.299, 0.587, 0.114 in Q1.14), rounded half up once,
    which is OpenCV's formula; it takes a pixel every cycle and stalls with the output stream.
    """
    width = beat_bytes(rgb.data)
    capacity = width + 2  # two bytes of a split pixel and one beat
    data, d_valid, length = rgb.data.data, rgb.data.valid, rgb.data.length
    d_ready = Signal(bool(0))
    bytes_in = Signal(intbv(0)[8 * capacity :])
    fill = Signal(intbv(0, min=0, max=capacity + 1))
    remaining = Signal(intbv(0)[len(length) :])
    # the pixel into the dot product, its luma out of it, and how many pixels are inside
    channels = [LUMA.signal() for _ in GRAY_WEIGHTS]
    offer, take, unit_ready = (Signal(bool(0)) for _ in range(3))
    luma, luma_valid = LUMA.signal(), Signal(bool(0))
    pixel = Signal(intbv(0)[8:])
    inside = Signal(intbv(0, min=0, max=dot_latency(len(GRAY_WEIGHTS)) + 2))
    accept, flush, empty = (Signal(bool(0)) for _ in range(3))
    drained, started = Signal(bool(0)), Signal(bool(0))
    bits = len(length)
    third = -(-(2 ** (bits + 1)) // 3)  # floor(n / 3) = n * third >> (bits + 1) for n < 2**bits
    out_length = gray.data.length
    text_done = Signal(bool(0))
    control = message_control(clk, rst, rgb, gray, drained, started, text_done)
    fields = image_fields(clk, rst, rgb, gray, GRAY, started, text_done)
    unit = constant_dot(clk, rst, offer, unit_ready, channels, luma_valid, accept, luma,
                        GRAY_WEIGHTS, LUMA)  # fmt: skip
    packer = beat_packer(clk, rst, pixel, luma_valid, accept, flush, gray.data, empty)
    red, green, blue = channels

    @always_comb
    def flow() -> None:
        offer.next = fill >= 3
        take.next = fill >= 3 and unit_ready
        if fill <= 2:
            d_ready.next = 1
        else:
            d_ready.next = fill <= 5 and fill >= 3 and unit_ready
        flush.next = rgb.valid and remaining == 0 and fill < 3 and inside == 0
        drained.next = rgb.valid and remaining == 0 and fill < 3 and inside == 0 and empty

    @always_comb
    def operands() -> None:
        red.next = bytes_in[8:0]
        green.next = bytes_in[16:8]
        blue.next = bytes_in[24:16]
        pixel.next = luma[8:0]  # 0 to 255: the weights sum to 1

    data_ready = rgb.data.ready

    @always_comb
    def ready() -> None:
        data_ready.next = d_ready

    @always_seq(clk.posedge, reset=rst)
    def count_inside() -> None:
        if take and not (luma_valid and accept):
            inside.next = inside + 1
        elif luma_valid and accept and not take:
            inside.next = inside - 1

    @always_seq(clk.posedge, reset=rst)
    def convert() -> None:
        out_length.next = (length * third) >> (bits + 1)
        held = intbv(0)[8 * capacity :]
        held[:] = bytes_in
        count = intbv(0, min=0, max=capacity + 1)
        count[:] = fill
        if take:
            held[:] = bytes_in >> 24
            count[:] = fill - 3
        if d_valid and d_ready:
            due = intbv(0)[bits:]
            due[:] = length if remaining == 0 else remaining
            got = intbv(0, min=0, max=width + 1)
            if due >= width:
                got[:] = width
            else:
                got[:] = due
            remaining.next = due - got
            for at in range(3):  # bit by bit: Verilog wants constant slice bounds
                if count == at:
                    for bit in range(8 * width):
                        held[8 * at + bit] = data[bit]
            count[:] = count + got
        if gray.valid and gray.ready:  # a split pixel's bytes do not reach the next message
            held[:] = 0
            count[:] = 0
        bytes_in.next = held
        fill.next = count

    return control, fields, unit, packer, flow, operands, ready, count_inside, convert


@block
def downscale(clk: Any, rst: Any, full: Any, small: Any) -> Any:
    """sensor_msgs/Image full (mono8) in, small (mono8) out: 2x2 box mean, a pixel per cycle."""
    byte, byte_valid, take = Signal(intbv(0)[8:]), Signal(bool(0)), Signal(bool(0))
    reader = byte_reader(clk, rst, full.data, byte, byte_valid, take)
    width, height = full.width, full.height
    column = Signal(intbv(0)[32:])
    odd_row = Signal(bool(0))
    left = Signal(intbv(0)[9:])  # as wide as `pair`: VHDL sizes a sum by its operands
    pair = Signal(intbv(0)[9:])
    above = Signal(intbv(0)[9:])
    pixel, pixel_valid = Signal(intbv(0)[8:]), Signal(bool(0))
    accept, flush, empty, drained, started = (Signal(bool(0)) for _ in range(5))
    store, fetch = Signal(bool(0)), Signal(bool(0))
    address = Signal(intbv(0, min=0, max=MAX_WIDTH // 2))
    memory = line_memory(clk, fetch, address, above, store, address, pair, MAX_WIDTH // 2)
    text_done = Signal(bool(0))
    control = message_control(clk, rst, full, small, drained, started, text_done)
    fields = image_fields(clk, rst, full, small, HALF_GRAY, started, text_done)
    packer = beat_packer(clk, rst, pixel, pixel_valid, accept, flush, small.data, empty)
    out_length = small.data.length
    bits = len(out_length)

    @always_comb
    def flow() -> None:
        take.next = byte_valid and (not pixel_valid or accept)
        pair.next = left + byte
        address.next = column[len(address) + 1 : 1]
        fetch.next = byte_valid and (not pixel_valid or accept) and not column[0]
        store.next = byte_valid and (not pixel_valid or accept) and column[0] and not odd_row
        flush.next = full.valid and not byte_valid and not pixel_valid
        drained.next = full.valid and not byte_valid and not pixel_valid and empty

    @always_seq(clk.posedge, reset=rst)
    def scale() -> None:
        half_width = intbv(0)[bits:]
        half_height = intbv(0)[bits:]
        half_width[:] = width[bits + 1 : 1]
        half_height[:] = height[bits + 1 : 1]
        product = intbv(0)[2 * bits :]
        product[:] = half_width * half_height
        out_length.next = product[bits:]
        if accept:
            pixel_valid.next = 0
        if take:
            if not column[0]:
                left.next = byte
            elif odd_row:
                box = intbv(0)[10:]  # as wide as the sum: VHDL sizes a sum by its operands
                box[9:] = above
                box[:] = box + pair + 2
                pixel.next = box[10:2]
                pixel_valid.next = 1
            if column == width - 1:
                column.next = 0
                odd_row.next = not odd_row
            else:
                column.next = column + 1
        if small.valid and small.ready:
            column.next = 0
            odd_row.next = 0

    return reader, memory, control, fields, packer, flow, scale


@block
def integral_image(clk: Any, rst: Any, image: Any, integral: Any) -> Any:
    """sensor_msgs/Image image (mono8) in, integral (32SC1) out: a pixel per cycle."""
    byte, byte_valid, take = Signal(intbv(0)[8:]), Signal(bool(0)), Signal(bool(0))
    reader = byte_reader(clk, rst, image.data, byte, byte_valid, take)
    width = image.width
    column = Signal(intbv(0)[32:])
    first_row = Signal(bool(1))
    # stage A: the pixel, where it is, and the sum above it read from the row memory
    a_valid, a_first_column, a_first_row = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    a_pixel = Signal(intbv(0)[8:])
    a_at = Signal(intbv(0, min=0, max=MAX_WIDTH))
    above = Signal(intbv(0)[32:])
    # stage B: the output value; the last write to the row memory, for a read at the same edge
    row_sum, row_now, total = (Signal(intbv(0)[32:]) for _ in range(3))
    written, written_at = Signal(intbv(0)[32:]), Signal(intbv(0, min=0, max=MAX_WIDTH))
    value, value_valid = Signal(intbv(0)[32:]), Signal(bool(0))
    advance, fetch, store = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    address = Signal(intbv(0, min=0, max=MAX_WIDTH))
    accept, flush, empty, drained, started = (Signal(bool(0)) for _ in range(5))
    memory = line_memory(clk, fetch, address, above, store, a_at, total, MAX_WIDTH)
    text_done = Signal(bool(0))
    control = message_control(clk, rst, image, integral, drained, started, text_done)
    fields = image_fields(clk, rst, image, integral, INTEGRAL, started, text_done)
    packer = beat_packer(clk, rst, value, value_valid, accept, flush, integral.data, empty)
    out_length, in_length = integral.data.length, image.data.length
    bits = len(out_length)
    wide = max(bits, len(in_length) + 2)  # four bytes per input pixel

    @always_comb
    def flow() -> None:
        advance.next = not value_valid or accept
        take.next = byte_valid and (not value_valid or accept)
        fetch.next = byte_valid and (not value_valid or accept)
        store.next = a_valid and (not value_valid or accept)
        address.next = column[len(address) :]
        running = intbv(0)[33:]  # sums wrap at 32 bits, as uint32 does
        if a_first_column:
            running[:] = a_pixel
        else:
            running[:] = row_sum + a_pixel
        row_now.next = running[32:]
        up = intbv(0)[32:]
        if a_first_row:
            up[:] = 0
        elif written_at == a_at:  # written at the edge `above` was read: not in it yet
            up[:] = written
        else:
            up[:] = above
        whole = intbv(0)[33:]
        whole[:] = running[32:] + up
        total.next = whole[32:]
        busy = byte_valid or a_valid or value_valid
        flush.next = image.valid and not busy
        drained.next = image.valid and not busy and empty

    @always_seq(clk.posedge, reset=rst)
    def accumulate() -> None:
        widened = intbv(0)[wide:]
        widened[len(in_length) + 2 : 2] = in_length
        out_length.next = widened[bits:]
        if advance:
            a_valid.next = byte_valid
            value_valid.next = a_valid
            if byte_valid:
                a_pixel.next = byte
                a_at.next = column[len(a_at) :]
                a_first_column.next = column == 0
                a_first_row.next = first_row
                if column == width - 1:
                    column.next = 0
                    first_row.next = 0
                else:
                    column.next = column + 1
            if a_valid:
                value.next = total
                written.next = total
                written_at.next = a_at
                row_sum.next = row_now
        if integral.valid and integral.ready:
            column.next = 0
            first_row.next = 1

    return reader, memory, control, fields, packer, flow, accumulate


@block
def message_control(clk: Any, rst: Any, incoming: Any, outgoing: Any, drained: Any,
                    started: Any, text_done: Any) -> Any:  # fmt: skip
    """The output message is valid once the stage has `drained`; the input goes with it.

    `started` is high from the input's first data beat (or its message) until the output
    message is taken: the stage works on a message. `text_done`: the encoding is sent.
    """
    in_valid, data_valid = incoming.valid, incoming.data.valid
    out_valid, out_ready = outgoing.valid, outgoing.ready
    done = Signal(bool(0))

    @always_comb
    def handshake() -> None:
        out_valid.next = done
        incoming.ready.next = done and out_ready

    @always_seq(clk.posedge, reset=rst)
    def sequence() -> None:
        if done and out_ready:
            done.next = 0
            started.next = 0
        else:
            if in_valid or data_valid:
                started.next = 1
            if drained and text_done and started and not done:
                done.next = 1

    return handshake, sequence


@block
def image_fields(clk: Any, rst: Any, incoming: Any, outgoing: Any, shape: Shape, started: Any,
                 text_done: Any) -> Any:  # fmt: skip
    """The output's header and size from the input; encoding, step and byte order if present."""
    blocks = [pass_header(incoming.header, outgoing.header)]
    blocks.append(image_size(incoming, outgoing, shape))
    if hasattr(outgoing, "encoding"):
        blocks.append(constant_text(clk, rst, shape.encoding, outgoing.encoding, started,
                                    text_done))  # fmt: skip
    else:
        blocks.append(constant(clk, rst, text_done, 1))
    if hasattr(outgoing, "is_bigendian"):
        blocks.append(constant(clk, rst, outgoing.is_bigendian, 0))
    return blocks


@block
def image_size(incoming: Any, outgoing: Any, shape: Shape) -> Any:
    """Height, width and step of the output (a downscaled output gets half of each)."""
    height, width = incoming.height, incoming.width
    out_height, out_width = outgoing.height, outgoing.width
    step = outgoing.step if hasattr(outgoing, "step") else Signal(intbv(0)[32:])
    shift = {1: 0, 4: 2}[shape.pixel_bytes]
    halve = shape.halved

    @always_comb
    def size() -> None:
        scaled = intbv(0)[32 + shift :]
        if halve:
            out_height.next = height >> 1
            out_width.next = width >> 1
            scaled[31 + shift : shift] = width[32:1]
        else:
            out_height.next = height
            out_width.next = width
            scaled[32 + shift : shift] = width
        step.next = scaled[32:]

    return size


@block
def constant(clk: Any, rst: Any, signal: Any, value: int) -> Any:
    """Drive `signal` with `value` (a register: MyHDL has no constant driver)."""

    @always_seq(clk.posedge, reset=rst)
    def hold() -> None:
        signal.next = value

    return hold
