"""Set Grant's "find the highest priority", vectorized: what the hardware's priority tree returns.

The hardware compares candidates pairwise in a balanced tree whose node keeps its left (lower
index) operand unless the right one is strictly better. For a total order that is the lowest
index among the best keys, which `first_candidate` and `least_key` compute directly; ROEDF's
wrap-around comparison is not transitive beyond its horizon, so `tree_least_modular` replays
the tree itself.
"""

from __future__ import annotations

import numpy as np

from rfc.lib.schedulers.model.statechart import BoolArray, IntArray


def first_candidate(candidates: BoolArray) -> IntArray:
    """int[R]: the lowest candidate index per replicate, or -1 (a priority encoder)."""
    index = np.argmax(candidates, axis=1)
    return np.where(candidates[np.arange(len(index)), index], index, -1)


def least_key(candidates: BoolArray, keys: IntArray) -> IntArray:
    """int[R]: the candidate with the smallest key, the lowest index on ties, or -1."""
    index = np.argmin(np.where(candidates, keys, np.iinfo(keys.dtype).max), axis=1)
    return np.where(candidates[np.arange(len(index)), index], index, -1)


def holder_first(keys: IntArray, owner: IntArray) -> IntArray:
    """Keys extended by one low bit that is 0 only for the holder: the holder wins ties."""
    extended = (keys << 1) | 1
    held = owner >= 0
    extended[np.nonzero(held)[0], owner[held]] -= 1
    return extended


def least_key_holder_first(candidates: BoolArray, keys: IntArray, owner: IntArray) -> IntArray:
    """`least_key` on `holder_first` keys, without building them: the holder wins ties."""
    best = least_key(candidates, keys)
    rows = np.arange(len(best))
    held = owner >= 0
    holder = np.maximum(owner, 0)
    keeps = held & (best >= 0) & candidates[rows, holder]
    keeps &= keys[rows, holder] == keys[rows, np.maximum(best, 0)]
    return np.where(keeps, owner, best)


def tree_least_modular(candidates: BoolArray, keys: IntArray, bits: int) -> IntArray:
    """int[R]: the tree's pick when key a beats b iff (a - b) mod 2^bits ≥ 2^(bits-1).

    Keys are compared as points on a circle (deadlines of a wrapping timer): exact while all
    candidates lie within half the circle of each other, and beyond that exactly what the
    hardware tree does.
    """
    batch, n = candidates.shape
    width = 2
    while width < n:
        width *= 2
    valid = np.zeros((batch, width), dtype=bool)
    valid[:, :n] = candidates
    key = np.zeros((batch, width), dtype=np.int64)
    key[:, :n] = keys
    index = np.broadcast_to(np.arange(width), (batch, width))
    mask, half = (1 << bits) - 1, 1 << (bits - 1)
    while width > 1:
        left_valid, right_valid = valid[:, 0::2], valid[:, 1::2]
        left_key, right_key = key[:, 0::2], key[:, 1::2]
        right_less = ((right_key - left_key) & mask) >= half
        take_right = right_valid & (~left_valid | right_less)
        valid = left_valid | right_valid
        key = np.where(take_right, right_key, left_key)
        index = np.where(take_right, index[:, 1::2], index[:, 0::2])
        width //= 2
    return np.where(valid[:, 0], index[:, 0], -1)
