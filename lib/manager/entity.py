"""The manager as one entity with a named port group per converter.

`chunk_demux` and `chunk_mux` take their converters as vectors (MyHDL top-level ports cannot be
lists); the system top level and the Vivado block design want one pin per converter signal. This
module builds the entity in between: ports ``sub<i>_t*`` towards subscriber i (its ``s_axis``),
``pub<j>_t*`` and ``pub<j>_length`` from publisher j (its ``m_axis`` and ``frame_length``), the
DMA's two streams ``s_axis_mm2s_*`` and ``m_axis_s2mm_*``, ``error_count``, and the drop
counters of each subscriber's gate or guard, ``status_sub<i>_<reason>``, which the manager
sends to the processor in a status chunk when asked (`rfc.lib.manager.status`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from myhdl import ConcatSignal, Signal, always, block, intbv

from rfc.lib.converters.malformed import DROP_REASONS, status_port
from rfc.lib.converters.ports import COUNTER_BITS, Direction, Port, PortRole
from rfc.lib.converters.toplevel import top_block
from rfc.lib.converters.wiring import follow, index_bit
from rfc.lib.manager.demux import ERROR_COUNT_BITS, chunk_demux
from rfc.lib.manager.header import BusGeometry
from rfc.lib.manager.mux import chunk_mux
from rfc.lib.manager.status import status_inserter
from rfc.lib.schedulers.spec import AnySchedulerSpec

#: Bits of a publisher's frame-length input.
LENGTH_BITS = 32


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


def _stream(prefix: str, width: int, source: bool) -> list[Port]:
    """An AXI-Stream port group; `source` when this entity drives tdata/tvalid."""
    out, into = (Direction.OUT, Direction.IN) if source else (Direction.IN, Direction.OUT)
    lanes = width // 8
    return [
        Port(f"{prefix}_tdata", width, out, PortRole.TDATA, prefix),
        Port(f"{prefix}_tkeep", lanes, out, PortRole.TKEEP, prefix),
        Port(f"{prefix}_tvalid", 1, out, PortRole.TVALID, prefix),
        Port(f"{prefix}_tready", 1, into, PortRole.TREADY, prefix),
        Port(f"{prefix}_tlast", 1, out, PortRole.TLAST, prefix),
    ]


def manager_ports(shape: ManagerShape) -> tuple[Port, ...]:
    """The manager's ports, in declaration order."""
    BusGeometry(shape.width)  # validates the width
    ports = [
        Port("clk", 1, Direction.IN, PortRole.CLOCK),
        Port("rst", 1, Direction.IN, PortRole.RESET),
        *_stream("s_axis_mm2s", shape.width, source=False),
        *_stream("m_axis_s2mm", shape.width, source=True),
        Port("error_count", ERROR_COUNT_BITS, Direction.OUT, PortRole.ERROR_COUNT),
    ]
    for index in range(shape.subscribers):
        ports += _stream(f"sub{index}", shape.width, source=True)
    ports += [
        Port(name, COUNTER_BITS, Direction.IN, PortRole.ERROR_COUNT)
        for name in status_inputs(shape.subscribers)
    ]
    for index in range(shape.publishers):
        ports += _stream(f"pub{index}", shape.width, source=False)
        ports.append(Port(f"pub{index}_length", LENGTH_BITS, Direction.IN, PortRole.FRAME_LENGTH))
    return tuple(ports)


def status_inputs(subscribers: int) -> list[str]:
    """The counter inputs in the order of the status chunk: by subscriber, then by reason."""
    return [status_port(i, reason) for i in range(subscribers) for reason in DROP_REASONS]


def manager_top(shape: ManagerShape, name: str) -> Any:
    """The manager as a MyHDL top-level block named `name`; call it with its port signals."""
    return top_block(name, [p.name for p in manager_ports(shape)], manager_body, shape=shape)


@block
def manager_body(shape: ManagerShape, **ports: Any) -> Any:
    """The demultiplexer fanned out to the subscribers, the multiplexer over the publishers."""
    width, lanes = shape.width, shape.width // 8
    parts: list[Any] = []
    n_sub, n_pub = shape.subscribers, shape.publishers

    # With no subscriber the DMA's stream still has to be read (MyHDL's std_logic ports need
    # every input used): a demultiplexer for one subscriber that is always ready drains it.
    # The runtime never sends to the logic then, as no subscriber id exists.
    fanout = max(n_sub, 1)
    tdata = Signal(intbv(0)[width:])
    tkeep = Signal(intbv(0)[lanes:])
    tlast = Signal(bool(0))
    tvalid = Signal(intbv(0)[fanout:])
    request = Signal(bool(0))
    if n_sub:
        tready, single = _vector([ports[f"sub{i}_tready"] for i in range(n_sub)])
        if single is not None:
            parts.append(follow(single, tready))
    else:
        tready = Signal(intbv(1)[1:])
    parts.append(
        chunk_demux(
            ports["clk"], ports["rst"], ports["s_axis_mm2s_tdata"],
            ports["s_axis_mm2s_tkeep"], ports["s_axis_mm2s_tvalid"],
            ports["s_axis_mm2s_tready"], ports["s_axis_mm2s_tlast"], tdata, tkeep, tlast,
            tvalid, tready, ports["error_count"], width=width, subscribers=fanout,
            status_request=request,
        )
    )  # fmt: skip
    for i in range(n_sub):
        parts += [
            follow(tdata, ports[f"sub{i}_tdata"]),
            follow(tkeep, ports[f"sub{i}_tkeep"]),
            follow(tlast, ports[f"sub{i}_tlast"]),
            index_bit(tvalid, i, ports[f"sub{i}_tvalid"]),
        ]

    # The publishers' chunks reach the DMA through the status inserter.
    out = {
        "tdata": Signal(intbv(0)[width:]),
        "tkeep": Signal(intbv(0)[lanes:]),
        "tvalid": Signal(bool(0)),
        "tlast": Signal(bool(0)),
    }
    out_ready = Signal(bool(0))
    counters = None
    if n_sub:
        counters, single = _vector([ports[name] for name in status_inputs(n_sub)])
        assert single is None  # four reasons per subscriber
    parts.append(
        status_inserter(
            ports["clk"], ports["rst"], request, counters, out["tdata"], out["tkeep"],
            out["tvalid"], out_ready, out["tlast"], ports["m_axis_s2mm_tdata"],
            ports["m_axis_s2mm_tkeep"], ports["m_axis_s2mm_tvalid"],
            ports["m_axis_s2mm_tready"], ports["m_axis_s2mm_tlast"], width=width,
            count=len(status_inputs(n_sub)),
        )
    )  # fmt: skip

    if n_pub:
        inputs = shape.scheduler.n
        grant = Signal(intbv(0)[inputs:])
        idle = {  # the inputs beyond the publishers never request
            "tdata": width, "tkeep": lanes, "tvalid": 1, "tlast": 1, "length": LENGTH_BITS
        }  # fmt: skip
        gathered = {}
        for name, bits in idle.items():
            signals = [ports[f"pub{i}_{name}"] for i in range(n_pub)]
            signals += [Signal(intbv(0)[bits:]) for _ in range(inputs - n_pub)]
            gathered[name], single = _vector(signals)
            if single is not None:
                parts.append(follow(single, gathered[name]))
        parts.append(
            chunk_mux(
                ports["clk"], ports["rst"], gathered["tdata"], gathered["tkeep"],
                gathered["tvalid"], grant, gathered["tlast"], gathered["length"],
                out["tdata"], out["tkeep"], out["tvalid"], out_ready, out["tlast"],
                width=width, scheduler=shape.scheduler,
            )
        )  # fmt: skip
        parts += [index_bit(grant, i, ports[f"pub{i}_tready"]) for i in range(n_pub)]
    else:
        parts.append(
            silent_output(ports["clk"], out["tdata"], out["tkeep"], out["tvalid"], out["tlast"])
        )
    return parts


def _vector(signals: list[Any]) -> tuple[Any, Any]:
    """One vector of the signals, the first in the lowest bits.

    Returns:
        The vector, and the signal to copy into it when there is only one (MyHDL's
        ConcatSignal needs two; the caller must instantiate the copy itself).
    """
    if len(signals) > 1:
        return ConcatSignal(*reversed(signals)), None
    return Signal(intbv(0)[len(signals[0]) :]), signals[0]


@block
def silent_output(clk: Any, tdata: Any, tkeep: Any, tvalid: Any, tlast: Any) -> Any:
    """No publishers: the PL→PS stream never sends."""

    @always(clk.posedge)
    def idle():
        tdata.next = 0
        tkeep.next = 0
        tvalid.next = 0
        tlast.next = 0

    return idle
