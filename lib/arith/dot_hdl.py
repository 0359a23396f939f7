"""MyHDL fixed-point dot product: N pairs per cycle, N multipliers, one rounding.

Each product runs through the DSP48E1's own registers (operand A/B, product M); a tree of
registered two-input adders sums them (its first level is the P register), and a fabric
register rounds half up and saturates to the format, as `rfc.lib.arith.mac_hdl` does. A pair
list enters every cycle (II = 1); results stay until taken (the whole pipeline stalls).
`constant_dot` multiplies by fixed coefficients instead of a second operand list, so a filter
or a colour conversion needs no coefficient ports. Latency: `rfc.lib.arith.dot.dot_latency`.
Bit-exact with `rfc.lib.arith.dot.dot_product`.
"""

from __future__ import annotations

from collections.abc import Sequence

from myhdl import Signal, always_seq, block

from rfc.lib.arith.dot import dot_latency, dot_sum_levels
from rfc.lib.arith.mac_hdl import round_to_format
from rfc.lib.arith.pipeline import delay_line, signed_signal, stage_register, stall_control
from rfc.lib.fixed import FixedFormat
from rfc.lib.types import Instances, SignalLike


# Signatures alike across rfc.lib blocks are its handshake convention, not a repeated idea.
@block
def fixed_dot(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    a: Sequence[SignalLike],
    b: Sequence[SignalLike],
    out_valid: SignalLike,
    out_ready: SignalLike,
    result: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """``Σ a[i] * b[i]`` in `fmt`, rounded half up and saturated (`dot.dot_product`).

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`; `a` and `b` (inputs, as
    many of each) and `result` (output) are raw integers of `fmt`, the operands' and result's
    format.
    """
    advance, valid_out = Signal(bool(0)), Signal(bool(0))
    datapath = dot_pipeline(clk, rst, advance, in_valid, a, b, valid_out, result, fmt)
    control = stall_control(valid_out, out_ready, advance, in_ready, out_valid)
    return datapath, control


# fixed_dot's body with constant `b`: a call to fixed_dot would rename the dot's registers.
@block
def constant_dot(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    a: Sequence[SignalLike],
    out_valid: SignalLike,
    out_ready: SignalLike,
    result: SignalLike,
    coefficients: tuple[int, ...],
    fmt: FixedFormat,
) -> Instances:
    """``Σ a[i] * coefficients[i]`` in `fmt`: `fixed_dot` with constant second operands.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`; `a` (inputs) and `result`
    (output) are raw integers of `fmt`, the operands' and result's format.

    Args:
        coefficients: Raw integers of `fmt`, one per input.

    Raises:
        ValueError: A coefficient outside `fmt`, or not one per input.
    """
    if len(coefficients) != len(a):
        raise ValueError(f"{len(a)} inputs need as many coefficients, not {len(coefficients)}")
    for value in coefficients:
        if not fmt.min_raw <= value <= fmt.max_raw:
            raise ValueError(
                f"coefficient {value} is outside the format ({fmt.min_raw} to {fmt.max_raw})"
            )
    advance, valid_out = Signal(bool(0)), Signal(bool(0))
    datapath = dot_pipeline(clk, rst, advance, in_valid, a, coefficients, valid_out, result, fmt)
    control = stall_control(valid_out, out_ready, advance, in_ready, out_valid)
    return datapath, control


@block
def dot_pipeline(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    valid_in: SignalLike,
    a: Sequence[SignalLike],
    b: Sequence[SignalLike] | Sequence[int],
    valid_out: SignalLike,
    result: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """The dot-product datapath without handshakes: it moves when `advance` is high.

    `b` holds signals or constant raw integers. A vector entering on a cycle with `advance`
    high comes out `dot_latency(len(a))` advancing cycles later, `valid_out` marking results.
    """
    products = [signed_signal(2 * fmt.width) for _ in a]
    parts = [
        constant_product(clk, rst, advance, x, y, p, fmt)
        if isinstance(y, int)
        else signal_product(clk, rst, advance, x, y, p)
        for x, y, p in zip(a, b, products, strict=True)
    ]
    level = products
    for _ in range(dot_sum_levels(len(a))):
        sums = []
        for k in range(0, len(level) - 1, 2):
            total = signed_signal(max(len(level[k]), len(level[k + 1])) + 1)
            parts.append(registered_add(clk, rst, advance, level[k], level[k + 1], total))
            sums.append(total)
        if len(level) % 2:
            late = Signal(level[-1].val)
            parts.append(stage_register(clk, rst, advance, level[-1], late))
            sums.append(late)
        level = sums
    rounded = fmt.signal()
    parts.append(round_to_format(level[0], rounded, fmt))
    parts.append(stage_register(clk, rst, advance, rounded, result))
    # one valid bit per register: operands, products, adder levels, rounded result
    parts.append(delay_line(clk, rst, advance, valid_in, valid_out, dot_latency(len(a)) + 1))
    return parts


@block
def signal_product(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    a: SignalLike,
    b: SignalLike,
    product: SignalLike,
) -> Instances:
    """``a * b`` through operand (A/B) and product (M) registers."""
    a1, b1 = Signal(a.val), Signal(b.val)

    @always_seq(clk.posedge, reset=rst)
    def stages() -> None:
        if advance:
            a1.next = a
            b1.next = b
            product.next = a1 * b1

    return stages


@block
def constant_product(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    a: SignalLike,
    coefficient: int,
    product: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """``a * coefficient`` through an operand (A) and a product (M) register."""
    a1 = Signal(a.val)
    # An undriven signal reaches VHDL and Verilog as a constant of its width.
    factor = fmt.signal(coefficient)

    @always_seq(clk.posedge, reset=rst)
    def stages() -> None:
        if advance:
            a1.next = a
            product.next = a1 * factor

    return stages


# Signatures of one-register blocks look alike across rfc.lib (engine's chain_stage).
@block
def registered_add(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    x: SignalLike,
    y: SignalLike,
    total: SignalLike,
) -> Instances:
    """``x + y``, registered: one node of the adder tree."""

    @always_seq(clk.posedge, reset=rst)
    def add() -> None:
        if advance:
            total.next = x + y

    return add
