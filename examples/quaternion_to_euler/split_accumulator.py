"""The iterative quaternion core's sums: a wide accumulator that adds a part of its bits per cycle.

A 110-bit product added to a 111-bit sum in one cycle is too long a carry chain for 100 MHz;
`split_accumulator` adds a third of the bits per cycle, each part's carry registered into the
next, so a sum is complete `ACCUMULATE_CYCLES` cycles after its product.
"""

from __future__ import annotations

from itertools import pairwise

from myhdl import Signal, always_comb, always_seq, block, intbv

#: Cycles after a product is summed until its sum is complete: a third of the bits per cycle.
ACCUMULATE_CYCLES = 3


@block
def split_accumulator(clk, rst, clear, add, subtract, product, total):
    """`total` plus or minus the signed `product`, a part of the sum per cycle, low part first.

    A 111-bit sum and its add-or-subtract in one cycle were the iterative core's critical path
    (5.37 ns of cells); here each cycle holds one part's carry chain, the part's carry
    registered for the next part on the next cycle. `total` is complete `ACCUMULATE_CYCLES`
    cycles after the cycle `add` or `subtract` is high; a sum may be added to on successive
    cycles. `clear` sets it to 0. Subtraction adds the complement plus 1.
    """
    width = len(total)
    bounds = [width * k // ACCUMULATE_CYCLES for k in range(ACCUMULATE_CYCLES + 1)]
    operand = Signal(intbv(0)[width:])
    first_carry = Signal(intbv(0)[1:])
    enable = Signal(bool(0))
    prepare = accumulator_operand(product, add, subtract, operand, first_carry, enable)
    values = [Signal(intbv(0)[high - low :]) for low, high in pairwise(bounds)]
    carries = [first_carry, *(Signal(intbv(0)[1:]) for _ in values)]
    parts = []
    for k, (low, high) in enumerate(pairwise(bounds)):
        addend, enabled = Signal(intbv(0)[high - low :]), Signal(bool(0))
        parts.append(delayed_by(clk, rst, operand(high, low), addend, k))
        parts.append(delayed_by(clk, rst, enable, enabled, k))
        parts.append(
            accumulator_part(clk, rst, clear, enabled, addend, carries[k], carries[k + 1],
                             values[k])
        )  # fmt: skip
    join = join_parts(values, total)
    return prepare, parts, join


@block
def accumulator_operand(product, add, subtract, operand, first_carry, enable):
    """`product` sign-extended to the sum's width, complemented to subtract (combinational)."""
    width = len(operand)
    product_bits = len(product)

    @always_comb
    def extend():
        extended = intbv(0)[width:]
        extended[product_bits:] = product[product_bits:]
        for i in range(product_bits, width):
            extended[i] = product[product_bits - 1]
        if subtract:
            operand.next = ~extended
            first_carry.next = 1
        else:
            operand.next = extended
            first_carry.next = 0
        enable.next = add or subtract

    return extend


@block
def delayed_by(clk, rst, source, delayed, cycles):
    """`source` registered `cycles` times (0: a wire)."""
    if cycles == 0:

        @always_comb
        def wire():
            delayed.next = source

        return wire
    chain = [source, *(Signal(delayed.val) for _ in range(cycles - 1)), delayed]
    return [register(clk, rst, before, after) for before, after in pairwise(chain)]


@block
def register(clk, rst, before, after):
    """One register."""

    @always_seq(clk.posedge, reset=rst)
    def hold():
        after.next = before

    return hold


@block
def accumulator_part(clk, rst, clear, enable, addend, carry_in, carry_out, value):
    """One part of a split sum: ``value + addend + carry_in`` on the cycles `enable` is high.

    The carry enters as a low bit below both operands (1 beside `value`, `carry_in` beside
    `addend`), so that the sum is one carry chain: Yosys maps a three-operand sum as two.
    """
    width = len(value)

    @always_seq(clk.posedge, reset=rst)
    def add():
        left = intbv(0)[width + 1 :]
        right = intbv(0)[width + 1 :]
        part_sum = intbv(0)[width + 2 :]
        if clear:
            value.next = 0
        elif enable:
            left[width + 1 : 1] = value
            left[0] = 1
            right[width + 1 : 1] = addend
            right[1:] = carry_in
            part_sum[:] = left + right
            value.next = part_sum[width + 1 : 1]
            carry_out.next = part_sum[width + 2 : width + 1]

    return add


@block
def join_parts(values, total):
    """The three parts of a split sum side by side, low part first, as one signed value."""
    width = len(total)
    low, middle, high = values
    low_bits, middle_bits = len(low), len(middle)

    @always_comb
    def join():
        whole = intbv(0)[width:]
        whole[low_bits:] = low
        whole[low_bits + middle_bits : low_bits] = middle
        whole[width : low_bits + middle_bits] = high
        total.next = whole.signed()

    return join
