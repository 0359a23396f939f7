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

from rfc.lib.arith.dot import dot_latency
from rfc.lib.arith.mac_hdl import adder_tree, round_to_format
from rfc.lib.arith.pipeline import delay_line, signed_signal, stage_register, stall_control
from rfc.lib.fixed import FixedFormat
from rfc.lib.types import Instances, SignalLike


# Signature and body (a datapath beside `stall_control`) are rfc.lib's handshake convention.
@block
def fixed_dot(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    a: Sequence[SignalLike],
    b: Sequence[SignalLike] | Sequence[int],
    out_valid: SignalLike,
    out_ready: SignalLike,
    result: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """``Σ a[i] * b[i]`` in `fmt`, rounded half up and saturated (`dot.dot_product`).

    Ports as in `rfc.lib.arith.pipeline`; `a` and `b` (inputs, as many of each) and `result`
    (output); `b` holds signals, or the constant raw integers `constant_dot` has checked.
    """
    advance, valid_out = Signal(bool(0)), Signal(bool(0))
    datapath = dot_pipeline(clk, rst, advance, in_valid, a, b, valid_out, result, fmt)
    control = stall_control(valid_out, out_ready, advance, in_ready, out_valid)
    return datapath, control


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

    Ports as in `rfc.lib.arith.pipeline`; `a` (inputs) and `result` (output).

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
    return fixed_dot(
        clk, rst, in_valid, in_ready, a, coefficients, out_valid, out_ready, result, fmt
    )


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
    total = signed_signal(2 * fmt.width + (len(a) - 1).bit_length())
    if len(a) == 1:  # a lone product still passes a register, as a sum's last level would
        parts.append(stage_register(clk, rst, advance, products[0], total))
    else:
        parts.append(adder_tree(clk, rst, advance, [(p, 0) for p in products], total))
    rounded = fmt.signal()
    parts.append(round_to_format(total, rounded, fmt))
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
