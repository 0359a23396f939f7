"""MyHDL fixed-point multiply and multiply-accumulate, pipelined for the DSP48.

The stages are the DSP48E1's own registers, so synthesis can fold them into the slice: operands
(A/B registers), product (M register), product or sum (P register); a fabric register then
rounds half up and saturates to the format. The multiply-accumulate forms its products with
`exact_multiply` (DSP48E1-sized limbs and a registered adder tree), so no cycle holds more than
one slice's product or one wide adder at any width. Both blocks take a pair every cycle
(II = 1) and hold results until taken (the whole pipeline stalls). Latencies, in cycles from
the input handshake to `out_valid`: `MULTIPLY_LATENCY`, `mac_latency`. Bit-exact with
`rfc.lib.arith.mac`.
"""

from __future__ import annotations

from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.arith.mac import MAC_GUARD_BITS
from rfc.lib.arith.pipeline import delay_line, signed_signal, stage_register, stall_control
from rfc.lib.fixed import FixedFormat
from rfc.lib.types import Instances, SignalLike

#: Operand (A/B), product (M), P and rounded-result registers: Yosys folds the first three into
#: a DSP48E1 (AREG, BREG, MREG, PREG all 1) when the operands fit one slice (25 x 18 signed).
MULTIPLY_LATENCY = 3


def mac_stages(fmt: FixedFormat) -> int:
    """Registers a pair passes in `mac_pipeline`: operands, the exact product's, sum, result."""
    return 3 + exact_multiply_stages(fmt.width, fmt.width)


def mac_latency(fmt: FixedFormat) -> int:
    """Cycles from `fixed_mac`'s input handshake to `out_valid` (the handshake loads a stage)."""
    return mac_stages(fmt) - 1


# Signatures alike across rfc.lib blocks are its handshake convention, not a repeated idea.
@block
def fixed_multiply(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    a: SignalLike,
    b: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    product: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """``product = a * b`` in `fmt`, rounded half up and saturated (`rfc.lib.arith.mac.multiply`).

    Ports as in `rfc.lib.arith.pipeline`; `a`, `b` (inputs) and `product` (output).
    """
    a1, b1 = fmt.signal(), fmt.signal()
    full, held = signed_signal(2 * fmt.width), signed_signal(2 * fmt.width)
    v1, v2, v3, v4 = (Signal(bool(0)) for _ in range(4))
    advance = Signal(bool(0))
    rounded = fmt.signal()
    rounding = round_to_format(held, rounded, fmt)

    # Shaped like every stage's registers (`cordic.hdl.cordic_pipeline`'s): these are the DSP's.
    @always_seq(clk.posedge, reset=rst)
    def stages() -> None:
        if advance:
            a1.next = a
            b1.next = b
            v1.next = in_valid
            full.next = a1 * b1
            v2.next = v1
            held.next = full
            v3.next = v2
            product.next = rounded
            v4.next = v3

    control = stall_control(v4, out_ready, advance, in_ready, out_valid)

    return rounding, stages, control


@block
def fixed_mac(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    a: SignalLike,
    b: SignalLike,
    first: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    total: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """Running ``Σ a * b`` in `fmt`: one result per pair, `first` starts a new sum.

    Each result is the sum since the last pair with `first` set, rounded half up and saturated
    (`rfc.lib.arith.mac.multiply_accumulate` of that prefix); sums of up to
    ``2**MAC_GUARD_BITS`` products never wrap.

    Ports as in `rfc.lib.arith.pipeline`; `a`, `b` (inputs) and `total` (output); `first`
    (input) starts a new sum with this pair.
    """
    advance = Signal(bool(0))
    valid_out = Signal(bool(0))
    datapath = mac_pipeline(clk, rst, advance, in_valid, a, b, first, valid_out, total, fmt)

    control = stall_control(valid_out, out_ready, advance, in_ready, out_valid)

    return datapath, control


@block
def mac_pipeline(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    valid_in: SignalLike,
    a: SignalLike,
    b: SignalLike,
    first: SignalLike,
    valid_out: SignalLike,
    result: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """The multiply-accumulate datapath without handshakes: it moves when `advance` is high.

    A pair entering on a cycle with `advance` high comes out `mac_stages` advancing cycles
    later, with `valid_out` marking cycles that carry a result. A new sum starts from half a
    unit of the result, so the rounding is a shift and the saturation alone.
    """
    stages = exact_multiply_stages(fmt.width, fmt.width)
    a1, b1 = fmt.signal(), fmt.signal()
    v1, f1, v2, f2, v3 = (Signal(bool(0)) for _ in range(5))
    product = signed_signal(2 * fmt.width)
    total = signed_signal(2 * fmt.width + MAC_GUARD_BITS)
    base = signed_signal(2 * fmt.width + MAC_GUARD_BITS)
    half = _half(fmt)
    rounded = fmt.signal()
    multiply = exact_multiply(clk, rst, advance, a1, b1, product)
    flags = [delay_line(clk, rst, advance, v1, v2, stages),
             delay_line(clk, rst, advance, f1, f2, stages)]  # fmt: skip
    saturation = saturate_to_format(total, rounded, fmt)

    @always_comb
    def start_or_continue() -> None:
        if f2:
            base.next = half
        else:
            base.next = total

    # Shaped like every stage's registers (`cordic.stage.micro_rotation`'s): these are the MAC's.
    @always_seq(clk.posedge, reset=rst)
    def registers() -> None:
        if advance:
            a1.next = a
            b1.next = b
            v1.next = valid_in
            f1.next = first
            if v2:
                total.next = base + product
            v3.next = v2
            result.next = rounded
            valid_out.next = v3

    return multiply, flags, saturation, start_or_continue, registers


def _half(fmt: FixedFormat) -> Signal:
    """Half a unit of `fmt` with ``2 * fmt.frac_bits`` fraction bits, as a signal.

    Constants wider than 31 bits reach VHDL as the initial values of undriven signals.
    """
    shift = fmt.frac_bits
    return Signal(intbv((1 << shift) >> 1, min=0, max=1 << shift))


@block
def round_to_format(wide: SignalLike, narrow: SignalLike, fmt: FixedFormat) -> Instances:
    """A value with ``2 * fmt.frac_bits`` fraction bits, rounded half up and saturated (comb)."""
    half = _half(fmt)
    biased = signed_signal(len(wide) + 1)

    @always_comb
    def add_half() -> None:
        biased.next = wide + half

    return add_half, saturate_to_format(biased, narrow, fmt)


@block
def saturate_to_format(biased: SignalLike, narrow: SignalLike, fmt: FixedFormat) -> Instances:
    """A value with ``2 * fmt.frac_bits`` fraction bits and half a unit added, rounded (comb).

    Rounding half up is then the shift alone; the result saturates to `fmt`'s range.
    """
    bits = len(biased)
    shift = fmt.frac_bits
    low, high = fmt.signal(fmt.min_raw), fmt.signal(fmt.max_raw)

    @always_comb
    def shift_and_saturate() -> None:
        v = intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1))
        v[:] = biased >> shift
        if v < low:
            narrow.next = low
        elif v > high:
            narrow.next = high
        else:
            narrow.next = v

    return shift_and_saturate


#: Operand limbs that fit one DSP48E1 multiplier (25 x 18 signed): unsigned low limbs of 24 and
#: 17 bits, the top limb signed.
_A_LIMB, _B_LIMB = 24, 17


def _limbs(width: int, size: int) -> list[tuple[int, int]]:
    """(low bit, bits) of each limb of a signed `width`-bit operand; the last one is signed."""
    count = max(1, -(-(width - 1) // size))
    return [(size * i, size if i < count - 1 else width - size * i) for i in range(count)]


def exact_multiply_stages(a_width: int, b_width: int) -> int:
    """Advancing cycles `exact_multiply` takes for operands of these widths."""
    terms = len(_limbs(a_width, _A_LIMB)) * len(_limbs(b_width, _B_LIMB))
    return 2 + (terms - 1).bit_length()


@block
def exact_multiply(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    a: SignalLike,
    b: SignalLike,
    product: SignalLike,
) -> Instances:
    """``a * b`` exact (`product` as wide as both operands), `exact_multiply_stages` later.

    The handshake-free product for larger pipelines. Operands wider than a DSP48E1 are cut into
    limbs that fit one (the caller's operand registers are its A/B registers); each limb
    product has its M and P register, and the shifted limb products are summed in a tree of
    registered two-input adders, so no path crosses a DSP and a wide adder at once.
    """
    a_limbs = [
        signed_signal(bits + (0 if low + bits == len(a) else 1))
        for low, bits in _limbs(len(a), _A_LIMB)
    ]
    b_limbs = [
        signed_signal(bits + (0 if low + bits == len(b) else 1))
        for low, bits in _limbs(len(b), _B_LIMB)
    ]
    cuts = [
        limb_cut(a, limb, low, bits)
        for (low, bits), limb in zip(_limbs(len(a), _A_LIMB), a_limbs, strict=True)
    ]
    cuts += [
        limb_cut(b, limb, low, bits)
        for (low, bits), limb in zip(_limbs(len(b), _B_LIMB), b_limbs, strict=True)
    ]
    terms, parts = [], []
    for (a_low, _), x in zip(_limbs(len(a), _A_LIMB), a_limbs, strict=True):
        for (b_low, _), y in zip(_limbs(len(b), _B_LIMB), b_limbs, strict=True):
            single = len(a_limbs) == len(b_limbs) == 1
            held = product if single else signed_signal(len(x) + len(y))
            parts.append(limb_product(clk, rst, advance, x, y, held))
            terms.append((held, a_low + b_low))
    if len(terms) > 1:
        parts.append(adder_tree(clk, rst, advance, terms, product))
    return cuts, parts


@block
def adder_tree(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    terms: list[tuple[SignalLike, int]],
    total: SignalLike,
) -> Instances:
    """``Σ term << shift`` over two or more `terms` (term, shift), into `total`, registered.

    A tree of two-input adders, a level per advancing cycle (``ceil(log2(len(terms)))``), the
    odd term of a level waiting in a register; `total` holds the sum wrapped to its width.
    """
    parts = []
    while len(terms) > 1:
        level = []
        for k in range(0, len(terms) - 1, 2):
            (x, x_shift), (y, y_shift) = sorted(terms[k : k + 2], key=lambda t: t[1])
            wide = max(len(x), len(y) + y_shift - x_shift) + 1
            node = total if len(terms) == 2 else signed_signal(wide)
            parts.append(shifted_add(clk, rst, advance, x, y, y_shift - x_shift, node))
            level.append((node, x_shift))
        if len(terms) % 2:
            late = Signal(terms[-1][0].val)
            parts.append(stage_register(clk, rst, advance, terms[-1][0], late))
            level.append((late, terms[-1][1]))
        terms = level
    return parts


@block
def limb_cut(operand: SignalLike, limb: SignalLike, low: int, bits: int) -> Instances:
    """One limb of a signed operand: the top one signed, the others unsigned (comb)."""
    top = low + bits == len(operand)

    @always_comb
    def signed_top() -> None:
        limb.next = operand >> low

    @always_comb
    def unsigned_low() -> None:
        limb.next = operand[low + bits : low]

    return signed_top if top else unsigned_low


@block
def limb_product(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    x: SignalLike,
    y: SignalLike,
    held: SignalLike,
) -> Instances:
    """A product that fits one DSP48E1, through its M and P registers."""
    full = Signal(held.val)

    @always_seq(clk.posedge, reset=rst)
    def stages() -> None:
        if advance:
            full.next = x * y
            held.next = full

    return stages


@block
def shifted_add(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    x: SignalLike,
    y: SignalLike,
    shift: int,
    total: SignalLike,
) -> Instances:
    """``x + (y << shift)``, registered (and wrapped to `total`'s width)."""
    if len(x) < len(total):

        @always_seq(clk.posedge, reset=rst)
        def add() -> None:
            if advance:
                total.next = x + (y << shift)

        return add
    # `total` is no wider than `x`: MyHDL's VHDL would then shift `y` within its own width,
    # losing its top bits. The sum is formed in a variable wide enough, then wrapped to `total`.
    bits = max(len(x), len(y) + shift) + 1
    kept = len(total)

    @always_seq(clk.posedge, reset=rst)
    def add_wrapped() -> None:
        if advance:
            wide = intbv(0, min=-(1 << (bits - 1)), max=1 << (bits - 1))
            wide[:] = y
            wide[:] = wide << shift
            wide[:] = wide + x
            total.next = wide[kept:].signed()

    return add_wrapped
