"""Pipelined (II = 1) float64 ↔ fixed converters with valid/ready handshakes.

`rfc.lib.fixed.pipeline`'s staged datapaths on one stall enable: each takes a value every
cycle, hands it over `FLOAT_TO_FIXED_LATENCY` (`FIXED_TO_FLOAT_LATENCY`) cycles after its input
handshake and holds it until taken; the bits are those of `rfc.lib.fixed.ieee754`.
"""

from __future__ import annotations

from myhdl import Signal, block

from rfc.lib.arith.pipeline import handshakes
from rfc.lib.fixed import FixedFormat
from rfc.lib.fixed.pipeline import (
    FIXED_TO_FLOAT_STAGES,
    FLOAT_TO_FIXED_STAGES,
    fixed_to_float_pipeline,
    float_to_fixed_pipeline,
)
from rfc.lib.types import Instances, SignalLike

#: Cycles from the input handshake to `out_valid` (the handshake loads the first stage).
FLOAT_TO_FIXED_LATENCY = FLOAT_TO_FIXED_STAGES - 1
#: Cycles from the input handshake to `out_valid`.
FIXED_TO_FLOAT_LATENCY = FIXED_TO_FLOAT_STAGES - 1


# Signatures alike across rfc.lib blocks are its handshake convention, not a repeated idea.
@block
def float_to_fixed_pipelined(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    bits: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    raw: SignalLike,
    overflow: SignalLike,
    invalid: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """Float64 bit pattern → raw `fmt`, ties to even, saturating (`ieee754.float_to_fixed`).

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`, the others as
    `float_to_fixed_pipeline`'s (its outputs held while `out_valid` waits for `out_ready`).
    """
    advance = Signal(bool(0))
    datapath = float_to_fixed_pipeline(clk, advance, bits, raw, overflow, invalid, fmt)
    stages = FLOAT_TO_FIXED_STAGES
    control = handshakes(clk, rst, in_valid, in_ready, out_valid, out_ready, advance, stages)
    return datapath, control


# Its float_to_fixed_pipelined twin wraps the other datapath: the shared part is `handshakes`.
@block
def fixed_to_float_pipelined(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    raw: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    bits: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """Raw `fmt` → float64 bit pattern, ties to even (`ieee754.fixed_to_float`).

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`, the others as
    `fixed_to_float_pipeline`'s (its output held while `out_valid` waits for `out_ready`).
    """
    advance = Signal(bool(0))
    datapath = fixed_to_float_pipeline(clk, advance, raw, bits, fmt)
    stages = FIXED_TO_FLOAT_STAGES
    control = handshakes(clk, rst, in_valid, in_ready, out_valid, out_ready, advance, stages)
    return datapath, control
