"""Set Grant's "find the max priority": a balanced comparison tree over the candidates.

Leaves are the N inputs (padded with invalid leaves to a power of two). Each node keeps its left
(lower-index) operand unless the right one is valid and strictly more urgent, so the root holds
the lowest index among the most urgent candidates. A node at level l carries an l-bit index
relative to its subtree, so a key-less tree (fixed priority) is a plain priority encoder.
"""

from __future__ import annotations

from typing import Any

from myhdl import Signal, always_comb, block, concat, intbv, modbv


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
    valid: Any,
    keys: list[Any],
    best: Any,
    best_valid: Any,
    best_key: Any,
    n: int,
    key_bits: int,
    modular: bool = False,
) -> Any:
    """Combinational argmin over the valid leaves.

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
    node_valid = {level: Signal(intbv(0)[width >> level :]) for level in range(levels + 1)}
    node_key = {
        level: [Signal(intbv(0)[kb:]) for _ in range(width >> level)] for level in range(levels + 1)
    }
    node_index = {
        level: [Signal(intbv(0)[level + 1 :]) for _ in range(width >> level)]
        for level in range(levels + 1)
    }
    parts = [tree_leaves(valid, keys, node_valid[0], node_key[0], node_index[0], n, key_bits)]
    for level in range(1, levels + 1):
        parts.append(
            tree_level(
                node_valid[level - 1],
                node_key[level - 1],
                node_index[level - 1],
                node_valid[level],
                node_key[level],
                node_index[level],
                width >> level,
                kb,
                modular,
            )
        )
    parts.append(
        tree_root(
            node_valid[levels], node_key[levels], node_index[levels], best, best_valid, best_key
        )
    )
    return parts


@block
def tree_leaves(
    valid: Any,
    keys: list[Any],
    leaf_valid: Any,
    leaf_key: list[Any],
    leaf_index: list[Any],
    n: int,
    bits: int,
):
    """Leaf level; without keys every key is the constant 0 (synthesis folds the comparators).

    Every leaf's index is a constant 0 bit below the bits the levels above add, so that all
    levels share one form; the root drops it.
    """
    width = len(leaf_index)
    if bits == 0:

        @always_comb
        def pass_valid():
            leaf_valid.next = valid
            for i in range(width):
                leaf_key[i].next = 0
                leaf_index[i].next = 0

        return pass_valid

    @always_comb
    def pass_leaves():
        leaf_valid.next = valid
        for i in range(width):
            leaf_index[i].next = 0
        for i in range(n):
            leaf_key[i].next = keys[i]

    return pass_leaves


@block
def tree_level(valid_in, key_in, index_in, valid_out, key_out, index_out, count, bits, modular):
    """One level of nodes: the right operand wins on the sign of (right - left).

    Bit `bits` of the zero-extended difference is the borrow of an unsigned comparison, bit
    `bits - 1` the sign of the wrap-around difference.
    """
    sign = bits - 1 if modular else bits

    @always_comb
    def nodes():
        diff = modbv(0)[bits + 1 :]
        for j in range(count):
            diff[:] = concat(False, key_in[2 * j + 1]) - concat(False, key_in[2 * j])
            valid_out.next[j] = valid_in[2 * j] or valid_in[2 * j + 1]
            if valid_in[2 * j + 1] and (not valid_in[2 * j] or diff[sign]):
                key_out[j].next = key_in[2 * j + 1]
                index_out[j].next = concat(True, index_in[2 * j + 1])
            else:
                key_out[j].next = key_in[2 * j]
                index_out[j].next = concat(False, index_in[2 * j])

    return nodes


@block
def tree_root(
    valid: Any, key: list[Any], index: list[Any], best: Any, best_valid: Any, best_key: Any
):
    """The root node's index, validity and key drive the tree's outputs."""
    top = len(best) + 1

    @always_comb
    def drive():
        best.next = index[0][top:1]
        best_valid.next = valid[0]
        best_key.next = key[0]

    return drive
