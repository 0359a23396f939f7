"""The ap_ctrl wrapper: runs a Vitis HLS core once per message and holds its results.

A core made with ``ap_ctrl_hs`` on its function, ``ap_none`` on its scalar inputs, ``ap_vld``
on its pointer outputs and ``ap_fifo`` on its streams (`rfc.hls.ports`) reads its fixed
inputs straight from the subscribers' registered fields. The wrapper starts it when every input
port is ready to be read (``ap_start`` held until ``ap_ready``): its message is valid, or the
first beat of its last stream has come — the subscriber sends a stream while the frame arrives
and raises the message's valid only at its end, and every field the core reads comes before a
port's last stream (`rfc.hls.ports` refuses other ports). A port's earlier streams are
held whole in FIFOs (`rfc.lib.converters.fifo`), so the subscriber can go on to the last one
before the core runs. Stream beats are handed to the core
element by element and its elements gathered into beats (`rfc.lib.hls.streams`); input lengths
are widened to the core's ``uint32_t``. The wrapper captures each output when its ``_ap_vld``
pulses and, on ``ap_done``, sends the output streams' last partial beats, offers each output
port's message until it is taken, and takes each input message once it is valid. Then it waits
for the next set of inputs: one call per message, as the HLS function is written.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, enum, intbv

from rfc.lib.converters.fifo import fifo
from rfc.lib.converters.wiring import follow, index_bit
from rfc.lib.hls.streams import pack_elements, unpack_beats
from rfc.lib.slice import part_of
from rfc.lib.types import Instances, SignalLike


@dataclass(frozen=True)
class StreamPort:
    """A sub-stream between a converter and the core's ``ap_fifo`` ports.

    Attributes:
        stream: Prefix of its converter-side pins: ``<stream>_tdata``, ``_tvalid``, ``_tready``
            (and from a subscriber ``_tkeep``, ``_tlast``).
        core: Prefix of the wrapper's pins toward the core: ``<core>_dout``, ``_empty_n``,
            ``_read`` for an input; ``<core>_din``, ``_full_n``, ``_write`` for an output.
        element: Bits of one element.
        beat: Bits of a beat (``tdata``).
        depth: Beats of the FIFO that holds it whole before the core starts (0: none).
    """

    stream: str
    core: str
    element: int
    beat: int
    depth: int = 0


@dataclass(frozen=True)
class AdapterShape:
    """What one wrapper serves.

    Attributes:
        inputs: Names of the input ports (their handshakes ``<p>_valid``/``<p>_ready``).
        outputs: Per output port, its name and its fields as ``(field port, core port, bits,
            core bits)``: the wrapper drives ``field port`` from the core's ``core port`` (as
            wide as the core makes it) and its ``_ap_vld``.
        sources: Per input port (in the order of `inputs`), its last stream, if any: its first
            beat starts the core as the message's valid does.
        sinks: The output ports' streams.
        lengths: Input stream lengths as ``(field port, core port, bits, core bits)``, widened.
        held: The input ports' other streams, each through a FIFO of its `StreamPort.depth`.
    """

    inputs: tuple[str, ...]
    outputs: tuple[tuple[str, tuple[tuple[str, str, int, int], ...]], ...]
    sources: tuple[StreamPort | None, ...] = ()
    sinks: tuple[StreamPort, ...] = ()
    lengths: tuple[tuple[str, str, int, int], ...] = ()
    held: tuple[StreamPort, ...] = ()


@block
def hls_adapter(shape: AdapterShape, **ports: SignalLike) -> Instances:
    """Instantiate the control, the stream adapters and one capture register per output."""
    parts = []
    inputs = max(len(shape.inputs), 1)
    outputs = max(len(shape.outputs), 1)
    # MyHDL needs blocks instantiated in the block's own body: no helper may call `follow`.
    valids = [ports[f"{p}_valid"] for p in shape.inputs]
    in_valid = _vector(valids)
    if len(valids) == 1:
        parts.append(follow(valids[0], in_valid))
    sources = shape.sources or (None,) * len(shape.inputs)
    starts = []
    for valid, source in zip(valids, sources, strict=True):
        if source is None:
            starts.append(valid)
        else:
            start = Signal(bool(0))
            parts.append(either(valid, ports[f"{source.stream}_tvalid"], start))
            starts.append(start)
    startable = _vector(starts)
    if len(starts) == 1:
        parts.append(follow(starts[0], startable))
    in_ready = Signal(intbv(0)[inputs:])
    out_valid = Signal(intbv(0)[outputs:])
    readies = [ports[f"{p}_ready"] for p, _ in shape.outputs]
    out_ready = _vector(readies)
    if len(readies) == 1:
        parts.append(follow(readies[0], out_ready))
    finished = Signal(bool(0))
    parts.append(
        ap_control(
            ports["clk"], ports["rst"], startable, in_valid, in_ready, ports["ap_start"],
            ports["ap_done"], ports["ap_ready"], out_valid, out_ready, finished,
        )
    )  # fmt: skip
    parts += [index_bit(in_ready, i, ports[f"{p}_ready"]) for i, p in enumerate(shape.inputs)]
    for index, (port, fields) in enumerate(shape.outputs):
        parts.append(index_bit(out_valid, index, ports[f"{port}_valid"]))
        parts += [
            capture(ports["clk"], ports["rst"], ports[core], ports[f"{core}_ap_vld"], ports[field])
            for field, core, _, _ in fields
        ]
    for field, core, _, _ in shape.lengths:
        parts.append(follow(ports[field], ports[core]))
    for source in (s for s in sources if s is not None):
        s, c = source.stream, source.core
        parts.append(
            unpack_beats(
                ports["clk"], ports["rst"], ports[f"{s}_tdata"], ports[f"{s}_tkeep"],
                ports[f"{s}_tvalid"], ports[f"{s}_tready"], ports[f"{c}_dout"],
                ports[f"{c}_empty_n"], ports[f"{c}_read"],
            )
        )  # fmt: skip
    for stream in shape.held:
        s, c, keep = stream.stream, stream.core, stream.beat // 8
        word = ConcatSignal(ports[f"{s}_tkeep"], ports[f"{s}_tdata"])
        shown = Signal(intbv(0)[stream.beat + keep :])
        tdata, tkeep = Signal(intbv(0)[stream.beat :]), Signal(intbv(0)[keep:])
        tvalid, tready = Signal(bool(0)), Signal(bool(0))
        parts += [
            fifo(ports["clk"], ports["rst"], word, ports[f"{s}_tvalid"], ports[f"{s}_tready"],
                 shown, tvalid, tready, stream.depth),
            part_of(shown, 0, stream.beat, False, tdata),
            part_of(shown, stream.beat, keep, False, tkeep),
            unpack_beats(ports["clk"], ports["rst"], tdata, tkeep, tvalid, tready,
                         ports[f"{c}_dout"], ports[f"{c}_empty_n"], ports[f"{c}_read"]),
        ]  # fmt: skip
    for sink in shape.sinks:
        s, c = sink.stream, sink.core
        parts.append(
            pack_elements(
                ports["clk"], ports["rst"], ports[f"{c}_din"], ports[f"{c}_full_n"],
                ports[f"{c}_write"], finished, ports[f"{s}_tdata"], ports[f"{s}_tvalid"],
                ports[f"{s}_tready"],
            )
        )  # fmt: skip
    return parts


def _vector(signals: Sequence[SignalLike]) -> SignalLike:
    """The signals as one vector, the first in bit 0; for one or none, a signal to drive."""
    if len(signals) > 1:
        return ConcatSignal(*reversed(signals))
    return Signal(intbv(1)[1:])


@block
def ap_control(
    clk: SignalLike,
    rst: SignalLike,
    startable: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    ap_start: SignalLike,
    ap_done: SignalLike,
    ap_ready: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    finished: SignalLike,
) -> Instances:
    """Start the core when every input can be read; after ``ap_done`` take and offer all."""
    everyone_in = (1 << len(in_valid)) - 1
    everyone_out = (1 << len(out_valid)) - 1
    phase_t = enum("WAIT_INPUTS", "RUNNING", "OFFERING")
    phase = Signal(phase_t.WAIT_INPUTS)
    started = Signal(bool(0))

    @always_seq(clk.posedge, reset=rst)
    def control() -> None:
        finished.next = 0
        if phase == phase_t.WAIT_INPUTS:
            if startable == everyone_in:
                ap_start.next = 1
                started.next = 0
                phase.next = phase_t.RUNNING
        elif phase == phase_t.RUNNING:
            if ap_ready:
                ap_start.next = 0
                started.next = 1
            if ap_done and (started or ap_ready):
                ap_start.next = 0
                in_ready.next = everyone_in
                out_valid.next = everyone_out
                finished.next = 1
                phase.next = phase_t.OFFERING
        else:
            waiting = intbv(0)[len(in_ready) :]  # input messages not taken yet
            for i in range(len(in_ready)):
                waiting[i] = in_ready[i] and not in_valid[i]
            in_ready.next = waiting
            pending = intbv(0)[len(out_valid) :]
            for i in range(len(out_valid)):
                pending[i] = out_valid[i] and not out_ready[i]
            out_valid.next = pending
            if pending == 0 and waiting == 0:
                phase.next = phase_t.WAIT_INPUTS

    return control


@block
def either(a: SignalLike, b: SignalLike, out: SignalLike) -> Instances:
    """Drive `out` with ``a or b``."""

    @always_comb
    def drive() -> None:
        out.next = a or b

    return drive


@block
def capture(
    clk: SignalLike, rst: SignalLike, core: SignalLike, valid: SignalLike, field: SignalLike
) -> Instances:
    """Hold a core output from the cycle its ``_ap_vld`` is high."""
    bits = len(field)  # a length: the core's uint32_t, the field as wide as its maximum

    @always_seq(clk.posedge, reset=rst)
    def hold() -> None:
        if valid:
            field.next = core[bits:]

    return hold
