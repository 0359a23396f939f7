"""The ap_ctrl wrapper: runs a Vitis HLS core once per message and holds its results.

A core made with ``ap_ctrl_hs`` on its function, ``ap_none`` on its scalar inputs and ``ap_vld``
on its pointer outputs (`rfc.lower.hls_signature`) reads its inputs straight from the
subscribers' registered fields. The wrapper starts it when every input port has a message
(``ap_start`` held until ``ap_ready``), captures each output when its ``_ap_vld`` pulses, and on
``ap_done`` takes the input messages and offers each output port's message until it is taken.
Then it waits for the next set of inputs: one call per message, as the HLS function is written.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from myhdl import ConcatSignal, Signal, always_seq, block, enum, intbv

from rfc.lib.converters.wiring import follow, index_bit


@dataclass(frozen=True)
class AdapterShape:
    """What one wrapper serves.

    Attributes:
        inputs: Names of the input ports (their handshakes ``<p>_valid``/``<p>_ready``).
        outputs: Per output port, its name and its fields as ``(field port, core port, bits)``:
            the wrapper drives ``field port`` from the core's ``core port`` and its ``_ap_vld``.
    """

    inputs: tuple[str, ...]
    outputs: tuple[tuple[str, tuple[tuple[str, str, int], ...]], ...]


@block
def hls_adapter(shape: AdapterShape, **ports: Any) -> Any:
    """Instantiate the control and one capture register per output field."""
    parts = []
    inputs = max(len(shape.inputs), 1)
    outputs = max(len(shape.outputs), 1)
    # MyHDL needs blocks instantiated in the block's own body: no helper may call `follow`.
    valids = [ports[f"{p}_valid"] for p in shape.inputs]
    in_valid = _vector(valids)
    if len(valids) == 1:
        parts.append(follow(valids[0], in_valid))
    in_ready = Signal(intbv(0)[inputs:])
    out_valid = Signal(intbv(0)[outputs:])
    readies = [ports[f"{p}_ready"] for p, _ in shape.outputs]
    out_ready = _vector(readies)
    if len(readies) == 1:
        parts.append(follow(readies[0], out_ready))
    parts.append(
        ap_control(
            ports["clk"], ports["rst"], in_valid, in_ready, ports["ap_start"], ports["ap_done"],
            ports["ap_ready"], out_valid, out_ready,
        )
    )  # fmt: skip
    parts += [index_bit(in_ready, i, ports[f"{p}_ready"]) for i, p in enumerate(shape.inputs)]
    for index, (port, fields) in enumerate(shape.outputs):
        parts.append(index_bit(out_valid, index, ports[f"{port}_valid"]))
        parts += [
            capture(ports["clk"], ports["rst"], ports[core], ports[f"{core}_ap_vld"], ports[field])
            for field, core, _ in fields
        ]
    return parts


def _vector(signals: Sequence[Any]) -> Any:
    """The signals as one vector, the first in bit 0; for one or none, a signal to drive."""
    if len(signals) > 1:
        return ConcatSignal(*reversed(signals))
    return Signal(intbv(1)[1:])


@block
def ap_control(
    clk: Any,
    rst: Any,
    in_valid: Any,
    in_ready: Any,
    ap_start: Any,
    ap_done: Any,
    ap_ready: Any,
    out_valid: Any,
    out_ready: Any,
) -> Any:
    """Start the core when every input is valid; offer every output after ``ap_done``."""
    everyone_in = (1 << len(in_valid)) - 1
    everyone_out = (1 << len(out_valid)) - 1
    phase_t = enum("WAIT_INPUTS", "RUNNING", "OFFERING")
    phase = Signal(phase_t.WAIT_INPUTS)
    started = Signal(bool(0))

    @always_seq(clk.posedge, reset=rst)
    def control() -> None:
        in_ready.next = 0
        if phase == phase_t.WAIT_INPUTS:
            if in_valid == everyone_in:
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
                phase.next = phase_t.OFFERING
        else:
            pending = intbv(0)[len(out_valid) :]
            for i in range(len(out_valid)):
                pending[i] = out_valid[i] and not out_ready[i]
            out_valid.next = pending
            if pending == 0:
                phase.next = phase_t.WAIT_INPUTS

    return control


@block
def capture(clk: Any, rst: Any, core: Any, valid: Any, field: Any) -> Any:
    """Hold a core output from the cycle its ``_ap_vld`` is high."""

    @always_seq(clk.posedge, reset=rst)
    def hold() -> None:
        if valid:
            field.next = core

    return hold
