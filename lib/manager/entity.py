"""The manager as one entity with a named port group per converter.

`chunk_demux` and `chunk_mux` take their converters as vectors (MyHDL top-level ports cannot be
lists); the system top level and the Vivado block design want one pin per converter signal. This
module builds the entity in between: ports ``sub<i>_t*`` towards subscriber i (its ``s_axis``),
``pub<j>_t*`` and ``pub<j>_length`` from publisher j (its ``m_axis`` and ``frame_length``), the
DMA's two streams ``s_axis_mm2s_*`` and ``m_axis_s2mm_*``, ``error_count``, and the drop
counters of each subscriber's gate or guard, ``status_sub<i>_<reason>``, which the manager
sends to the processor in a status chunk when asked (`rfc.lib.manager.status`). Every stream
crosses a register slice at the entity's edge (`rfc.lib.manager.boundary`), so each signal
the manager hands on comes from a flip-flop.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from myhdl import ConcatSignal, Signal, always, always_comb, block, intbv

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.malformed import DROP_REASONS, status_port
from rfc.lib.converters.ports import (
    COUNTER_BITS,
    Direction,
    Port,
    PortRole,
    axis_ports,
    clock_ports,
)
from rfc.lib.converters.toplevel import top_block
from rfc.lib.converters.wiring import follow, index_bit
from rfc.lib.manager.boundary import routed_slice, slice_chain, stream_like
from rfc.lib.manager.demux import ERROR_COUNT_BITS, chunk_demux
from rfc.lib.manager.header import BusGeometry
from rfc.lib.manager.mux import chunk_mux
from rfc.lib.manager.status import status_inserter
from rfc.lib.schedulers.spec import AnySchedulerSpec
from rfc.lib.slice import SliceSide, parts_slice
from rfc.lib.types import Instances, SignalLike

#: Bits of a publisher's frame-length input.
LENGTH_BITS = 32
#: Register slices in a row in front of each publisher: room for four beats, so a publisher
#: finishes its frame and starts the next while the scheduler still grants the one before.
PUBLISHER_SLICES = 2


@dataclass(frozen=True)
class ManagerShape:
    """What a manager serves.

    Attributes:
        width: Bus width in bits.
        subscribers: Number of subscriber converters (wire ids 0 … subscribers-1).
        publishers: Number of publisher converters (wire ids 0 … publishers-1).
        scheduler: The scheduler of the publishers (None when there are none). It may have
            more inputs than there are publishers (a lone publisher still needs a scheduler of
            two, the smallest the generator builds); the extra inputs never request.
    """

    width: int
    subscribers: int
    publishers: int
    scheduler: AnySchedulerSpec | None

    def __post_init__(self) -> None:
        inputs = 0 if self.scheduler is None else self.scheduler.n
        if inputs < self.publishers or (self.publishers == 0 and inputs):
            raise ValueError(f"a scheduler of {inputs} inputs for {self.publishers} publishers")


def manager_ports(shape: ManagerShape) -> tuple[Port, ...]:
    """The manager's ports, in declaration order."""
    BusGeometry(shape.width)  # validates the width
    ports = [
        *clock_ports(),
        *axis_ports("s_axis_mm2s", shape.width // 8, Direction.IN),
        *axis_ports("m_axis_s2mm", shape.width // 8, Direction.OUT),
        Port("error_count", ERROR_COUNT_BITS, Direction.OUT, PortRole.ERROR_COUNT),
    ]
    for index in range(shape.subscribers):
        ports += axis_ports(f"sub{index}", shape.width // 8, Direction.OUT)
    ports += [
        Port(name, COUNTER_BITS, Direction.IN, PortRole.ERROR_COUNT)
        for name in status_inputs(shape.subscribers)
    ]
    for index in range(shape.publishers):
        ports += axis_ports(f"pub{index}", shape.width // 8, Direction.IN)
        ports.append(Port(f"pub{index}_length", LENGTH_BITS, Direction.IN, PortRole.FRAME_LENGTH))
    return tuple(ports)


def status_inputs(subscribers: int) -> list[str]:
    """The counter inputs in the order of the status chunk: by subscriber, then by reason."""
    return [status_port(i, reason) for i in range(subscribers) for reason in DROP_REASONS]


def manager_top(shape: ManagerShape, name: str) -> Callable[..., Instances]:
    """The manager as a MyHDL top-level block named `name`; call it with its port signals."""
    return top_block(name, [p.name for p in manager_ports(shape)], manager_body, shape=shape)


@block
def manager_body(shape: ManagerShape, **ports: SignalLike) -> Instances:
    """The demultiplexer fanned out to the subscribers, the multiplexer over the publishers."""
    width, lanes = shape.width, shape.width // 8
    clk, rst = ports["clk"], ports["rst"]
    parts: list[Instances] = []
    n_sub, n_pub = shape.subscribers, shape.publishers

    # The DMA's MM2S stream, registered on the way in.
    dma_in = [ports[f"s_axis_mm2s_{name}"] for name in ("tdata", "tkeep", "tlast")]
    mm2s = stream_like(dma_in)
    mm2s_valid, mm2s_ready = Signal(bool(0)), Signal(bool(0))
    dma_side = SliceSide(dma_in, ports["s_axis_mm2s_tvalid"], ports["s_axis_mm2s_tready"])
    parts.append(parts_slice(clk, rst, dma_side, SliceSide(mm2s, mm2s_valid, mm2s_ready)))

    # With no subscriber the DMA's stream still has to be read (MyHDL's std_logic ports need
    # every input used): a demultiplexer for one subscriber that is always ready drains it.
    # The runtime never sends to the logic then, as no subscriber id exists.
    fanout = max(n_sub, 1)
    beat = stream_like(mm2s)
    tvalid = Signal(intbv(0)[fanout:])
    taken = Signal(bool(0))
    tready = Signal(intbv(0)[fanout:])
    request = Signal(bool(0))
    parts.append(spread_bit(taken, tready))
    parts.append(
        chunk_demux(
            clk, rst, AxiStream(mm2s[0], mm2s[1], mm2s_valid, mm2s_ready, mm2s[2]),
            AxiStream(beat[0], beat[1], tvalid, tready, beat[2]),
            ports["error_count"], width=width, subscribers=fanout, status_request=request,
        )
    )  # fmt: skip
    # Registered on the way out to the subscribers.
    routed = stream_like(beat)
    sub_valid = Signal(intbv(0)[fanout:])
    if n_sub:
        sub_ready, single = _vector([ports[f"sub{i}_tready"] for i in range(n_sub)])
        if single is not None:
            parts.append(follow(single, sub_ready))
    else:
        sub_ready = Signal(intbv(1)[1:])
    parts.append(routed_slice(clk, rst, beat, tvalid, taken, routed, sub_valid, sub_ready))
    for i in range(n_sub):
        parts += [
            follow(routed[0], ports[f"sub{i}_tdata"]),
            follow(routed[1], ports[f"sub{i}_tkeep"]),
            follow(routed[2], ports[f"sub{i}_tlast"]),
            index_bit(sub_valid, i, ports[f"sub{i}_tvalid"]),
        ]

    # The publishers' chunks reach the DMA through the status inserter and a last slice.
    out = AxiStream(
        tdata=Signal(intbv(0)[width:]),
        tkeep=Signal(intbv(0)[lanes:]),
        tvalid=Signal(bool(0)),
        tready=Signal(bool(0)),
        tlast=Signal(bool(0)),
    )
    s2mm = AxiStream(*stream_like(out.signals()))
    counters = None
    if n_sub:
        counters, single = _vector([ports[name] for name in status_inputs(n_sub)])
        assert single is None  # four reasons per subscriber
    parts.append(
        status_inserter(
            clk, rst, request, counters, out, s2mm, width=width,
            count=len(status_inputs(n_sub)),
        )
    )  # fmt: skip
    dma_out = [ports[f"m_axis_s2mm_{name}"] for name in ("tdata", "tkeep", "tlast")]
    dma_side = SliceSide(dma_out, ports["m_axis_s2mm_tvalid"], ports["m_axis_s2mm_tready"])
    s2mm_side = SliceSide([s2mm.tdata, s2mm.tkeep, s2mm.tlast], s2mm.tvalid, s2mm.tready)
    parts.append(parts_slice(clk, rst, s2mm_side, dma_side))

    if n_pub:
        parts.append(publisher_inputs(shape, clk, rst, ports, out))
    else:
        parts.append(silent_output(clk, out))
    return parts


@block
def publisher_inputs(
    shape: ManagerShape,
    clk: SignalLike,
    rst: SignalLike,
    ports: dict[str, SignalLike],
    out: AxiStream,
) -> Instances:
    """Each publisher's stream and length through a slice, then the multiplexer over them."""
    assert shape.scheduler is not None
    width, lanes, n_pub = shape.width, shape.width // 8, shape.publishers
    inputs = shape.scheduler.n
    parts: list[Instances] = []
    names = ("tdata", "tkeep", "tlast", "length")
    sliced: dict[str, list[SignalLike]] = {name: [] for name in (*names, "tvalid", "tready")}
    for i in range(n_pub):
        sources = [ports[f"pub{i}_{name}"] for name in names]
        sinks = stream_like(sources)
        valid, ready = Signal(bool(0)), Signal(bool(0))
        parts.append(
            slice_chain(
                clk,
                rst,
                SliceSide(sources, ports[f"pub{i}_tvalid"], ports[f"pub{i}_tready"]),
                SliceSide(sinks, valid, ready),
                stages=PUBLISHER_SLICES,
            )
        )
        for name, sink in zip(names, sinks, strict=True):
            sliced[name].append(sink)
        sliced["tvalid"].append(valid)
        sliced["tready"].append(ready)
    grant = Signal(intbv(0)[inputs:])
    idle = {  # the inputs beyond the publishers never request
        "tdata": width, "tkeep": lanes, "tvalid": 1, "tlast": 1, "length": LENGTH_BITS
    }  # fmt: skip
    gathered = {}
    for name, bits in idle.items():
        signals = sliced[name] + [Signal(intbv(0)[bits:]) for _ in range(inputs - n_pub)]
        gathered[name], single = _vector(signals)
        if single is not None:
            parts.append(follow(single, gathered[name]))
    parts.append(
        chunk_mux(
            clk, rst,
            AxiStream(gathered["tdata"], gathered["tkeep"], gathered["tvalid"], grant,
                      gathered["tlast"]),
            gathered["length"],
            out, width=width, scheduler=shape.scheduler,
        )
    )  # fmt: skip
    parts += [index_bit(grant, i, sliced["tready"][i]) for i in range(n_pub)]
    return parts


# One bit to every bit: shaped like the statechart's grant gate, which selects a vector.
@block
def spread_bit(bit: SignalLike, vector: SignalLike) -> Instances:
    """Drive every bit of `vector` with `bit`."""
    ones = 2 ** len(vector) - 1

    @always_comb
    def copy() -> None:
        if bit:
            vector.next = ones
        else:
            vector.next = 0

    return copy


def _vector(signals: list[SignalLike]) -> tuple[SignalLike, SignalLike]:
    """One vector of the signals, the first in the lowest bits.

    Returns:
        The vector, and the signal to copy into it when there is only one (MyHDL's
        ConcatSignal needs two; the caller must instantiate the copy itself).
    """
    if len(signals) > 1:
        return ConcatSignal(*reversed(signals)), None
    return Signal(intbv(0)[len(signals[0]) :]), signals[0]


@block
def silent_output(clk: SignalLike, out: AxiStream) -> Instances:
    """No publishers: the PL→PS stream `out` never sends (its ``tready`` is not read)."""
    tdata, tkeep, tvalid, _, tlast = out.signals()

    @always(clk.posedge)
    def idle() -> None:
        tdata.next = 0
        tkeep.next = 0
        tvalid.next = 0
        tlast.next = 0

    return idle
