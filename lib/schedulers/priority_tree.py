"""Set Grant's "find the max priority": a balanced comparison tree over the candidates.

Leaves are the N inputs (padded with invalid leaves to a power of two). Each node keeps its left
(lower-index) operand unless the right one is valid and strictly more urgent, so the root holds
the lowest index among the most urgent candidates. A node at level l carries an l-bit index
relative to its subtree, so a key-less tree (fixed priority) is a plain priority encoder.
"""

from __future__ import annotations

from myhdl import Constant, Signal, always_comb, block, concat, intbv, modbv

from rfc.lib.converters.wiring import index_bit
from rfc.lib.types import Instances, SignalLike


def tree_width(n: int) -> int:
    """Number of leaves: the smallest power of two >= max(n, 2)."""
    width = 2
    while width < n:
        width *= 2
    return width


def index_bits(n: int) -> int:
    """Bits of an input index (at least 1)."""
    return tree_width(n).bit_length() - 1


@block
def priority_tree(
    valid: SignalLike,
    keys: list[SignalLike],
    best: SignalLike,
    best_valid: SignalLike,
    best_key: SignalLike,
    n: int,
    key_bits: int,
    modular: bool = False,
) -> Instances:
    """Combinational argmin over the valid leaves.

    Every node is its own block on its own signals (no arrays of signals): each is driven on
    every path, and GHDL's synthesis infers no memory from the tree.

    Args:
        valid: intbv[n] signal, the candidates.
        keys: n signals of `key_bits` (smaller is more urgent), or [] for index order.
        best: Output, index of the winner.
        best_valid: Output, some leaf is valid.
        best_key: Output, the winner's key (unused when `keys` is empty).
        n: Number of inputs.
        key_bits: Width of a key (0 without keys).
        modular: Compare keys on a circle: a beats b iff (a - b) mod 2^key_bits has its top
            bit set (ROEDF's wrapping deadlines).
    """
    width = tree_width(n)
    levels = width.bit_length() - 1
    kb = max(key_bits, 1)
    sign = kb - 1 if modular else kb
    parts = []
    node_valid, node_key, node_index = [], [], []
    for i in range(width):
        # Leaves: each index is a constant 0 bit below the bits the levels above add, so that
        # all levels share one form; the root drops it. Padding and key-less leaves are
        # constants (synthesis folds their comparators).
        node_index.append(Constant(intbv(0)[1:]))
        node_key.append(keys[i] if key_bits and i < n else Constant(intbv(0)[kb:]))
        if i < n:
            leaf = Signal(bool(0))
            parts.append(index_bit(valid, i, leaf))
            node_valid.append(leaf)
        else:
            node_valid.append(Constant(bool(0)))
    live = n  # leaves, then nodes, with a candidate below
    for level in range(1, levels + 1):
        valid_out, key_out, index_out = [], [], []
        for j in range(width >> level):
            if 2 * j >= live:  # only padding below: a padding node
                valid_out.append(Constant(bool(0)))
                key_out.append(Constant(intbv(0)[kb:]))
                index_out.append(Constant(intbv(0)[level + 1 :]))
                continue
            valid_out.append(Signal(bool(0)))
            key_out.append(Signal(intbv(0)[kb:]))
            index_out.append(Signal(intbv(0)[level + 1 :]))
            parts.append(
                tree_node(
                    node_valid[2 * j],
                    node_valid[2 * j + 1],
                    node_key[2 * j],
                    node_key[2 * j + 1],
                    node_index[2 * j],
                    node_index[2 * j + 1],
                    valid_out[j],
                    key_out[j],
                    index_out[j],
                    kb,
                    sign,
                )
            )
        node_valid, node_key, node_index = valid_out, key_out, index_out
        live = -(-live // 2)  # nodes of this level with a candidate below
    parts.append(tree_root(node_valid[0], node_key[0], node_index[0], best, best_valid, best_key))
    return parts


@block
def tree_node(
    valid_l: SignalLike,
    valid_r: SignalLike,
    key_l: SignalLike,
    key_r: SignalLike,
    index_l: SignalLike,
    index_r: SignalLike,
    valid_out: SignalLike,
    key_out: SignalLike,
    index_out: SignalLike,
    bits: int,
    sign: int,
) -> Instances:
    """One node: the right operand wins on the sign of (right - left).

    Bit `bits` of the zero-extended difference is the borrow of an unsigned comparison, bit
    `bits - 1` the sign of the wrap-around difference.
    """

    @always_comb
    def node() -> None:
        diff = modbv(0)[bits + 1 :]
        diff[:] = concat(False, key_r) - concat(False, key_l)
        valid_out.next = valid_l or valid_r
        if valid_r and (not valid_l or diff[sign]):
            key_out.next = key_r
            index_out.next = concat(True, index_r)
        else:
            key_out.next = key_l
            index_out.next = concat(False, index_l)

    return node


@block
def tree_root(
    valid: SignalLike,
    key: SignalLike,
    index: SignalLike,
    best: SignalLike,
    best_valid: SignalLike,
    best_key: SignalLike,
) -> Instances:
    """The root node's index, validity and key drive the tree's outputs."""
    top = len(best) + 1

    @always_comb
    def drive() -> None:
        best.next = index[top:1]
        best_valid.next = valid
        best_key.next = key

    return drive
